// The words of render/visibility/VisibilityTables.h that the visibility strategy's passes read:
// items and primitive records, and how a visibility-buffer id names its unit. Bindings apart
// (visibility_geometry.wgsl binds the tables; the binning binds its own).

const kUnitTriangles = 256u;
const kItemWords = 4u;
const kPrimitiveWords = 32u;
const kItemRecord = 1u;  // Item's word: its primitive record.

// Primitive record fields (word offsets).
const kIndexOffset = 0u;   // Byte offset of index 0, or of nothing when not indexed.
const kIndexSize = 1u;     // 0 (not indexed), 2 or 4.
const kTriangleCount = 2u;
const kMaterial = 3u;
// Shading bin (render/visibility/MaterialBins.h: its block's first material * 2 + 1 with a bound
// TANGENT) in the low 26 bits (kBinMask), the material's slot in the bin's block above
// (kBinSlotShift).
const kBin = 4u;
const kBinSlotShift = 26u;
const kBinMask = (1u << kBinSlotShift) - 1u;
const kDoubleSided = 5u;
const kPosition = 6u;
const kNormal = 9u;
const kTexcoord0 = 12u;
const kTexcoord1 = 15u;
const kColor = 18u;
const kTangent = 21u;
const kBoundsCenter = 24u;
const kBoundsExtent = 27u;
