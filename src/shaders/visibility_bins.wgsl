// The visibility strategy's shading bins, for one view: every covered pixel (at several
// samples, each distinct triangle of a pixel: its first sample) sorted by the bin of its
// triangle's primitive (material, and whether TANGENT is bound: the shader variants of
// the shading pass), so that each bin is shaded by one dispatch with its material's bind group.
//   countMain    one thread per pixel of the viewport: counts its bins;
//   offsetsMain  one thread: each bin's first slot in the pixel list;
//   scatterMain  one thread per pixel: writes its entries into their bins' slots.
#include "visibility_bin_record.wgsl"
#include "visibility_params.wgsl"

struct Bin {
    count: atomic<u32>,
    cursor: atomic<u32>,
    first: u32,
    padding: array<u32, kBinPaddingWords>,
}

@group(0) @binding(0) var<uniform> params: VisibilityParams;
@group(0) @binding(1) var<storage, read> tables: array<u32>;
@group(0) @binding(2) var<storage, read> units: array<vec2u>;
@group(0) @binding(3) var<storage, read> visibility: array<vec2u>;
@group(0) @binding(4) var<storage, read_write> bins: array<Bin>;
@group(0) @binding(5) var<storage, read_write> pixels: array<u32>;

const kNoBin = 0xffffffffu;

// The shading bin of each sample of pixel `id` of the viewport (kNoBin: not covered, or the
// triangle of an earlier sample of the pixel, which is shaded once) and the pixel's first entry
// in the visibility buffer.
struct PixelBins {
    first: u32,
    bins: array<u32, 4>,
}

fn pixelBins(id: vec3u) -> PixelBins {
    var result: PixelBins;
    result.bins = array<u32, 4>(kNoBin, kNoBin, kNoBin, kNoBin);
    if (id.x >= params.viewportWidth || id.y >= params.viewportHeight) {
        return result;
    }
    result.first = ((id.y + params.viewportY) * params.targetWidth + id.x + params.viewportX) *
                   params.samples;
    var ids = array<u32, 4>(0u, 0u, 0u, 0u);  // The triangles of the samples in `covered`.
    var covered = 0u;
    for (var sample = 0u; sample < params.samples; sample++) {
        let key = visibility[result.first + sample];
        if (key.y == 0u) {
            continue;
        }
        ids[sample] = key.x;
        covered |= 1u << sample;
        var seen = false;
        for (var earlier = 0u; earlier < sample; earlier++) {
            seen = seen || (((covered >> earlier) & 1u) != 0u && ids[earlier] == key.x);
        }
        if (!seen) {
            let unit = units[key.x / 256u];
            let record = tables[unit.x * 4u + 1u];
            result.bins[sample] = tables[record + 4u];
        }
    }
    return result;
}

// Counted and reserved per workgroup first, then added to the bins once per workgroup and bin:
// a global atomic per pixel on the few addresses of a frame's bins serialised in the GPU's L2
// (on the H100 about the whole pass for a 1280x720 frame of one or two bins). Frames of more
// bins than kLocalBins count each pixel globally.
const kLocalBins = 64u;  // One per thread of a workgroup.
var<workgroup> localCounts: array<atomic<u32>, kLocalBins>;
var<workgroup> localFirst: array<u32, kLocalBins>;

@compute @workgroup_size(8, 8)
fn countMain(@builtin(global_invocation_id) id: vec3u,
             @builtin(local_invocation_index) local: u32) {
    let grouped = params.binCount <= kLocalBins;
    atomicStore(&localCounts[local], 0u);
    workgroupBarrier();
    let pixel = pixelBins(id);
    for (var sample = 0u; sample < params.samples; sample++) {
        let bin = pixel.bins[sample];
        if (bin != kNoBin) {
            if (grouped) {
                atomicAdd(&localCounts[bin], 1u);
            } else {
                atomicAdd(&bins[bin].count, 1u);
            }
        }
    }
    workgroupBarrier();
    let count = atomicLoad(&localCounts[local]);
    if (grouped && count > 0u) {
        atomicAdd(&bins[local].count, count);
    }
}

@compute @workgroup_size(1)
fn offsetsMain() {
    var first = 0u;
    for (var b = 0u; b < params.binCount; b++) {
        let count = atomicLoad(&bins[b].count);
        bins[b].first = first;
        first += count;
    }
}

// Lists each shaded sample's visibility-buffer entry (pixel * samples + sample) in its bin: the
// workgroup's entries of a bin in one range reserved at once (as countMain counts them).
@compute @workgroup_size(8, 8)
fn scatterMain(@builtin(global_invocation_id) id: vec3u,
               @builtin(local_invocation_index) local: u32) {
    let grouped = params.binCount <= kLocalBins;
    atomicStore(&localCounts[local], 0u);
    workgroupBarrier();
    let pixel = pixelBins(id);
    var slots = array<u32, 4>(0u, 0u, 0u, 0u);
    for (var sample = 0u; sample < params.samples; sample++) {
        let bin = pixel.bins[sample];
        if (bin != kNoBin) {
            if (grouped) {
                slots[sample] = atomicAdd(&localCounts[bin], 1u);
            } else {
                let slot = atomicAdd(&bins[bin].cursor, 1u);
                pixels[bins[bin].first + slot] = pixel.first + sample;
            }
        }
    }
    workgroupBarrier();
    let count = atomicLoad(&localCounts[local]);
    if (grouped && count > 0u) {
        localFirst[local] = bins[local].first + atomicAdd(&bins[local].cursor, count);
    }
    workgroupBarrier();
    if (grouped) {
        for (var sample = 0u; sample < params.samples; sample++) {
            let bin = pixel.bins[sample];
            if (bin != kNoBin) {
                pixels[localFirst[bin] + slots[sample]] = pixel.first + sample;
            }
        }
    }
}
