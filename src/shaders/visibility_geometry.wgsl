// What every pass of the visibility strategy reads (render/visibility/VisibilityTables.h writes
// it): the view's parameters, the GPU scene's shared geometry buffer (vertices and indices pulled
// here, in any glTF component type), the instance transforms, and the tables of primitives and
// items (instance x primitive), all in group 1. Needs frame.wgsl.
//
// A visibility-buffer id is unit * 256 + triangle in the unit; a unit is one cluster (up to 256
// consecutive triangles) of one item: (item, word index of the cluster's record), entry
// id / 256 of the units buffer. That entry is the scene's unit table's, written once per scene
// (VisibilityTables::unitTable: the same id for a triangle every run), or where the table does
// not fit, the culling pass's list for this view (visibility_raster.wgsl's unitId).

#include "visibility_params.wgsl"
#include "visibility_layout.wgsl"

struct Transform {
    world: mat4x4f,
    normal: mat4x4f,
}

// An attribute as the tables describe it: byte offset of element 0 in the geometry buffer,
// stride, and format (0: absent; else kind | components << 8 | normalized << 16).
struct Attribute {
    offset: u32,
    stride: u32,
    format: u32,
}

// Item: instance slot, primitive record (word index), its first word of the clusters'
// visibility (visibility_raster.wgsl; a word per cluster of every level, in record order), 1
// when mirrored.
struct Item {
    slot: u32,
    record: u32,
    clusterWords: u32,
    mirrored: u32,
}

#if VIEW_SLOTS
// A pass over several views side by side (the shading pass): each view's parameters and frame
// uniform in a 256-byte slot (VisibilityStrategy's view slots), the first of the views bound at
// a dynamic offset; `params` and `frame` are set per pixel to the slot of the view it lies in.
struct ViewSlot {
    @size(64) params: VisibilityParams,
    @size(192) frame: Frame,
}
const kSlotViews = 256u;  // 64 KiB, the uniform binding's limit.
@group(1) @binding(0) var<uniform> viewSlots: array<ViewSlot, kSlotViews>;
var<private> params: VisibilityParams;
var<private> selectedSlot = 0xffffffffu;

// Selects the slot of the view that `pixel` lies in; copies it only when it changes (a thread's
// entries mostly lie in one view: every one in frames of one view).
fn selectViewOf(pixel: vec2u) {
    let slot = min((pixel.x - viewSlots[0].params.viewportX) / viewSlots[0].params.viewportWidth,
                   kSlotViews - 1u);
    if (slot != selectedSlot) {
        selectedSlot = slot;
        params = viewSlots[slot].params;
        frame = viewSlots[slot].frame;
    }
}
#else
@group(1) @binding(0) var<uniform> params: VisibilityParams;
#endif
@group(1) @binding(1) var<storage, read> geometry: array<u32>;
@group(1) @binding(2) var<storage, read> instances: array<Transform>;
@group(1) @binding(3) var<storage, read> tables: array<u32>;

fn loadItem(index: u32) -> Item {
    let base = index * kItemWords;
    return Item(tables[base], tables[base + 1u], tables[base + 2u], tables[base + 3u]);
}

// Cluster record fields (word offsets; VisibilityTables.h): its triangles, counted from level
// 0's first index, and its bounds, object space. A radius of kNeverCulled or more (a primitive
// without clusters, split into runs of 256 triangles) is culled by nothing, a cutoff above 1 by
// no facing.
const kClusterFirstTriangle = 0u;
const kClusterTriangles = 1u;  // | kClusterAlone for the only cluster of its level.
const kClusterCenter = 2u;
const kClusterRadius = 5u;
const kClusterConeApex = 6u;
const kClusterConeAxis = 9u;
const kClusterConeCutoff = 12u;
const kClusterWords = 13u;
const kClusterAlone = 0x80000000u;
const kNeverCulled = 1e29;

// The triangle of `unit` that visibility-buffer id `id` names.
fn unitTriangle(unit: vec2u, id: u32) -> u32 {
    return tables[unit.y + kClusterFirstTriangle] + id % kUnitTriangles;
}

fn field(record: u32, offset: u32) -> u32 {
    return tables[record + offset];
}

fn attributeAt(record: u32, offset: u32) -> Attribute {
    return Attribute(tables[record + offset], tables[record + offset + 1u],
                     tables[record + offset + 2u]);
}

fn vec3At(record: u32, offset: u32) -> vec3f {
    return bitcast<vec3f>(vec3u(tables[record + offset], tables[record + offset + 1u],
                                tables[record + offset + 2u]));
}

// `bytes` (1, 2 or 4) little-endian bytes at any byte address of the geometry buffer.
fn loadBits(address: u32, bytes: u32) -> u32 {
    let word = address >> 2u;
    let shift = (address & 3u) * 8u;
    var value = geometry[word] >> shift;
    if (shift + bytes * 8u > 32u) {
        value |= geometry[word + 1u] << (32u - shift);
    }
    if (bytes < 4u) {
        value &= (1u << (bytes * 8u)) - 1u;
    }
    return value;
}

// Component kinds: 1 int8, 2 uint8, 3 int16, 4 uint16, 5 uint32, 6 float32.
fn componentSize(kind: u32) -> u32 {
    return select(select(4u, 2u, kind == 3u || kind == 4u), 1u, kind <= 2u);
}

fn loadComponent(address: u32, kind: u32, normalized: bool) -> f32 {
    switch (kind) {
        case 1u: {
            let v = f32(bitcast<i32>(loadBits(address, 1u) << 24u) >> 24u);
            return select(v, max(v / 127.0, -1.0), normalized);
        }
        case 2u: {
            let v = f32(loadBits(address, 1u));
            return select(v, v / 255.0, normalized);
        }
        case 3u: {
            let v = f32(bitcast<i32>(loadBits(address, 2u) << 16u) >> 16u);
            return select(v, max(v / 32767.0, -1.0), normalized);
        }
        case 4u: {
            let v = f32(loadBits(address, 2u));
            return select(v, v / 65535.0, normalized);
        }
        case 5u: {
            return f32(loadBits(address, 4u));
        }
        default: {
            return bitcast<f32>(loadBits(address, 4u));
        }
    }
}

// The attribute of `vertex`, its missing components (or all, when absent) from `fallback`.
fn loadAttribute(source: Attribute, vertex: u32, fallback: vec4f) -> vec4f {
    var result = fallback;
    if (source.format == 0u) {
        return result;
    }
    let kind = source.format & 0xffu;
    let count = (source.format >> 8u) & 0xffu;
    let normalized = ((source.format >> 16u) & 1u) != 0u;
    let size = componentSize(kind);
    let base = source.offset + vertex * source.stride;
    if (kind == 6u && (base & 3u) == 0u) {
        // Aligned 32-bit floats, what most positions, normals and coordinates are: whole words.
        let word = base >> 2u;
        for (var c = 0u; c < count; c++) {
            result[c] = bitcast<f32>(geometry[word + c]);
        }
        return result;
    }
    for (var c = 0u; c < count; c++) {
        result[c] = loadComponent(base + c * size, kind, normalized);
    }
    return result;
}

// The vertex index of a triangle's corner.
fn vertexIndex(record: u32, triangle: u32, corner: u32) -> u32 {
    let i = triangle * 3u + corner;
    let size = field(record, kIndexSize);
    if (size == 0u) {
        return i;
    }
    return loadBits(field(record, kIndexOffset) + i * size, size);
}

// What mesh.wgsl's vertex shader computes, in the same order (so the same rounding).
fn worldPosition(record: u32, transform: Transform, vertex: u32) -> vec4f {
    let position = loadAttribute(attributeAt(record, kPosition), vertex, vec4f(0.0)).xyz;
    return transform.world * vec4f(position, 1.0);
}

fn clipPosition(world: vec4f) -> vec4f {
    return frame.projection * frame.view * world;
}
