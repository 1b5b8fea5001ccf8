// The visibility strategy's shading bins, for one group of views: each 8x8 tile of pixels is
// listed in every bin (material, and whether TANGENT is bound: the shader variants of the
// shading pass) that the triangle of one of its samples falls in, so that each bin is shaded by
// one dispatch with its material's bind group, a workgroup per listed tile (visibility_shade.wgsl
// shades the tile's samples of that bin, each distinct triangle of a pixel once).
// One dispatch lists a round of up to kRoundBins bins, from VisibilityParams.firstBin: each bin
// of the round has room for every tile of the group in one buffer, so a tile is listed with one
// atomic per bin it holds and no count, prefix sum or second pass (on the H100 those three
// dispatches over every pixel took 0.043 ms of a 1280x720 frame). Scenes of more bins bin and
// shade round after round. Scenes of one bin are not binned: their shading takes every tile
// (visibility_shade.wgsl's everyTile).
// COMPOSED (frames composed in compute at one sample): uncovered pixels take the background in
// the composed frame, whose covered ones the shading writes (visibility_composed.wgsl).
#include "visibility_bin_record.wgsl"
#include "visibility_layout.wgsl"
#include "visibility_params.wgsl"
#include "visibility_pixel.wgsl"

struct Bin {
    count: atomic<u32>,  // Tiles listed.
    id: u32,             // The bin's index (for the shading, which binds one record).
    first: u32,          // Its first tile in the list.
    everyTile: u32,      // 0: the binning clears the record (visibility_shade.wgsl's Bin).
    padding: array<u32, kBinPaddingWords>,
}

@group(0) @binding(0) var<uniform> params: VisibilityParams;
@group(0) @binding(1) var<storage, read> tables: array<u32>;
@group(0) @binding(2) var<storage, read> units: array<vec2u>;
@group(0) @binding(3) var<storage, read> visibility: array<vec2u>;
@group(0) @binding(4) var<storage, read_write> bins: array<Bin>;
// Per bin of the round, tiles as (tile column | tile row << 16) of the target.
@group(0) @binding(5) var<storage, read_write> tiles: array<u32>;
#if COMPOSED
#include "visibility_composed.wgsl"
@group(0) @binding(6) var composedFrame: ComposedFrame;
@group(0) @binding(7) var<uniform> composition: Composition;
#endif

const kNoBin = 0xffffffffu;

// The shading bin of each sample of pixel `id` of the viewport (kNoBin: not covered, or the
// triangle of an earlier sample of the pixel, which is shaded once).
fn pixelBins(id: vec3u) -> array<u32, 4> {
    var result = array<u32, 4>(kNoBin, kNoBin, kNoBin, kNoBin);
    if (id.x >= params.viewportWidth || id.y >= params.viewportHeight) {
        return result;
    }
    let first = ((id.y + params.viewportY) * params.targetWidth + id.x + params.viewportX) *
                params.samples;
    let taken = distinctSamples(first, params.samples);
    for (var sample = 0u; sample < params.samples; sample++) {
        if ((taken.mask & (1u << sample)) != 0u) {
            let unit = units[taken.ids[sample] / kUnitTriangles];
            let record = tables[unit.x * kItemWords + kItemRecord];
            result[sample] = tables[record + kBin] & kBinMask;  // The bin, not the slot.
        }
    }
    return result;
}

// The bins of the round a workgroup's tile has listed itself in, a bit each.
var<workgroup> listed: array<atomic<u32>, kRoundBins / 32u>;

@compute @workgroup_size(8, 8)
fn binMain(@builtin(global_invocation_id) id: vec3u,
           @builtin(workgroup_id) group: vec3u,
           @builtin(local_invocation_index) local: u32) {
    if (local < kRoundBins / 32u) {
        atomicStore(&listed[local], 0u);
    }
    workgroupBarrier();
    let sampleBins = pixelBins(id);
    // The group's viewport starts on a tile (its views from a multiple of kSlotViews).
    let tile = (params.viewportX / 8u + group.x) | ((params.viewportY / 8u + group.y) << 16u);
    let tilesPerBin = ((params.viewportWidth + 7u) / 8u) * ((params.viewportHeight + 7u) / 8u);
    for (var sample = 0u; sample < params.samples; sample++) {
        let bin = sampleBins[sample];
        if (bin == kNoBin || bin < params.firstBin || bin - params.firstBin >= kRoundBins) {
            continue;
        }
        let inRound = bin - params.firstBin;
        let bit = 1u << (inRound % 32u);
        if ((atomicOr(&listed[inRound / 32u], bit) & bit) == 0u) {
            let first = inRound * tilesPerBin;
            let slot = atomicAdd(&bins[bin].count, 1u);
            if (slot == 0u) {
                bins[bin].id = bin;
                bins[bin].first = first;
            }
            tiles[first + slot] = tile;
        }
    }
#if COMPOSED
    // One sample: a pixel without a bin is uncovered. Every round writes it (the same value):
    // rounds without a bin the scene uses are not dispatched, the first among them.
    if (all(id.xy < vec2u(params.viewportWidth, params.viewportHeight)) &&
        sampleBins[0] == kNoBin) {
        storeComposed(id.xy + vec2u(params.viewportX, params.viewportY), vec4f(0.0));
    }
#endif
}
