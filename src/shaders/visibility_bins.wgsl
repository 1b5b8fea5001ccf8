// The visibility strategy's shading bins, for one view: every covered pixel sorted by the bin
// of its triangle's primitive (material, and whether TANGENT is bound: the shader variants of
// the shading pass), so that each bin is shaded by one indirect dispatch with its material's
// bind group.
//   countMain    one thread per pixel of the viewport: counts its bin;
//   offsetsMain  one thread: each bin's first slot in the pixel list and its dispatch size;
//   scatterMain  one thread per pixel: writes its index into its bin's slots.
#include "visibility_bin_record.wgsl"
#include "visibility_params.wgsl"


struct Bin {
    count: atomic<u32>,
    cursor: atomic<u32>,
    first: u32,
    // dispatchWorkgroupsIndirect arguments (byte offset 12).
    x: u32,
    y: u32,
    z: u32,
    padding: array<u32, kBinPaddingWords>,
}

@group(0) @binding(0) var<uniform> params: VisibilityParams;
@group(0) @binding(1) var<storage, read> tables: array<u32>;
@group(0) @binding(2) var<storage, read> units: array<vec2u>;
@group(0) @binding(3) var<storage, read> visibility: array<vec2u>;
@group(0) @binding(4) var<storage, read_write> bins: array<Bin>;
@group(0) @binding(5) var<storage, read_write> pixels: array<u32>;

// The pixel's index in the visibility buffer and its bin, or 0xffffffff where nothing covers it.
fn pixelBin(id: vec3u) -> vec2u {
    if (id.x >= params.viewportWidth || id.y >= params.viewportHeight) {
        return vec2u(0u, 0xffffffffu);
    }
    let index = (id.y + params.viewportY) * params.targetWidth + id.x + params.viewportX;
    let key = visibility[index];
    if (key.y == 0u) {
        return vec2u(index, 0xffffffffu);
    }
    let unit = units[key.x / 256u];
    let record = tables[unit.x * 4u + 1u];
    return vec2u(index, tables[record + 4u]);
}

@compute @workgroup_size(8, 8)
fn countMain(@builtin(global_invocation_id) id: vec3u) {
    let bin = pixelBin(id);
    if (bin.y != 0xffffffffu) {
        atomicAdd(&bins[bin.y].count, 1u);
    }
}

@compute @workgroup_size(1)
fn offsetsMain() {
    var first = 0u;
    for (var b = 0u; b < params.binCount; b++) {
        let count = atomicLoad(&bins[b].count);
        bins[b].first = first;
        let groups = (count + 63u) / 64u;
        bins[b].x = min(groups, 65535u);
        bins[b].y = max(1u, (groups + 65534u) / 65535u);
        bins[b].z = 1u;
        first += count;
    }
}

@compute @workgroup_size(8, 8)
fn scatterMain(@builtin(global_invocation_id) id: vec3u) {
    let bin = pixelBin(id);
    if (bin.y != 0xffffffffu) {
        let slot = atomicAdd(&bins[bin.y].cursor, 1u);
        pixels[bins[bin.y].first + slot] = bin.x;
    }
}
