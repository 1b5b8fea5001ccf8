enable atomic_vec2u_min_max;

// The visibility strategy's hardware path, for one view, where the compute raster does not take
// every triangle (VisibilityParams.computeTakesAll): the triangles it listed whole (near- or
// far-plane crossings, large ones, those past its full lists; back faces culled already), drawn
// with one indirect draw, vertices pulled from the shared buffers as the compute raster pulls
// them, and each fragment (sample) writing (depth, id) into the visibility buffer with the same
// 64-bit atomic.
#include "frame.wgsl"
#include "visibility_geometry.wgsl"

@group(1) @binding(4) var<storage, read> units: array<vec2u>;
@group(1) @binding(5) var<storage, read> hardwareList: array<u32>;
@group(1) @binding(6) var<storage, read_write> visibility: array<atomic<vec2u>>;

struct VertexOutput {
    @builtin(position) position: vec4f,
    @location(0) @interpolate(flat) id: u32,
}

@vertex
fn vertexMain(@builtin(vertex_index) vertex: u32) -> VertexOutput {
    var output: VertexOutput;
    let slot = vertex / 3u;
    if (slot >= params.hardwareCapacity) {
        output.position = vec4f(2.0, 2.0, 2.0, 1.0);  // Outside: clipped.
        return output;
    }
    let id = hardwareList[slot];
    let unit = units[id / kUnitTriangles];
    let item = loadItem(unit.x);
    let triangle = unitTriangle(unit, id);
    let index = vertexIndex(item.record, triangle, vertex % 3u);
    output.position = clipPosition(worldPosition(item.record, instances[item.slot], index));
    output.id = id;
    return output;
}

// Runs per sample (sample_index) into a target of params.samples samples: the position and its
// depth are the sample's, and each covered sample writes its own entry.
@fragment
fn fragmentMain(input: VertexOutput, @builtin(sample_index) sample: u32) {
    // The pass's attachment is the view's size, the view at its origin (VisibilityTarget's
    // ensureHardwareDepth): the pixel in the strip is the view's offset further.
    let pixel = vec2u(input.position.xy) + vec2u(params.viewportX, params.viewportY);
    let depth = ~bitcast<u32>(clamp(input.position.z, 0.0, 1.0));
    let index = (pixel.y * params.targetWidth + pixel.x) * params.samples + sample;
    atomicStoreMax(&visibility[index], vec2u(input.id, depth));
}
