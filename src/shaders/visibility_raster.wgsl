enable atomic_vec2u_min_max;

// The visibility strategy's compute passes before shading, for one view:
//   cullMain    one thread per item (instance x primitive): its bounds against the frustum; a
//               visible item appends its units (256 triangles each) to the unit list;
//   argsMain    one thread: the raster dispatch's size from the unit count;
//   rasterMain  one workgroup per unit, one thread per triangle at a time: clip, cull back
//               faces, snap to 1/256 pixel and cover pixel centres with edge functions under the
//               top-left rule, writing (depth, id) with a 64-bit atomic max of
//               (id, ~depth bits), so the nearest depth wins. Triangles that cross the near or
//               far plane, or whose screen bounds exceed params.maxComputePixels, are listed
//               for the hardware pass (visibility_hardware.wgsl) instead.
#include "frame.wgsl"
#include "visibility_geometry.wgsl"

struct Counters {
    unitCount: atomic<u32>,
    padding0: u32,
    padding1: u32,
    padding2: u32,
    // drawIndirect arguments of the hardware pass (byte offset 16): 3 vertices per listed
    // triangle.
    hardwareVertices: atomic<u32>,
    hardwareInstances: u32,
    hardwareFirstVertex: u32,
    hardwareFirstInstance: u32,
    computeTriangles: atomic<u32>,  // Triangles the compute raster covered pixels of (or not).
    hardwareOverflow: atomic<u32>,  // Triangles the full hardware list could not take.
    hardwareTriangles: atomic<u32>,  // Triangles the hardware list took.
}

@group(1) @binding(4) var<storage, read_write> units: array<vec2u>;
@group(1) @binding(5) var<storage, read_write> counters: Counters;
@group(1) @binding(6) var<storage, read_write> hardwareList: array<u32>;
@group(1) @binding(7) var<storage, read_write> visibility: array<atomic<vec2u>>;
// dispatchWorkgroupsIndirect arguments of rasterMain, written by argsMain (bound alone with the
// counters: a buffer read as indirect arguments cannot be writable in the same dispatch).
@group(1) @binding(8) var<storage, read_write> rasterArguments: vec3u;

const kMaxGroups = 65535u;

// Whether a sphere lies wholly outside one of the frustum's planes (WebGPU depth 0..w).
fn outsideFrustum(center: vec3f, radius: f32) -> bool {
    let m = frame.projection * frame.view;
    let row0 = vec4f(m[0][0], m[1][0], m[2][0], m[3][0]);
    let row1 = vec4f(m[0][1], m[1][1], m[2][1], m[3][1]);
    let row2 = vec4f(m[0][2], m[1][2], m[2][2], m[3][2]);
    let row3 = vec4f(m[0][3], m[1][3], m[2][3], m[3][3]);
    let planes = array<vec4f, 6>(row3 + row0, row3 - row0, row3 + row1, row3 - row1, row2,
                                 row3 - row2);
    for (var i = 0u; i < 6u; i++) {
        let plane = planes[i];
        if (dot(plane.xyz, center) + plane.w < -radius * length(plane.xyz)) {
            return true;
        }
    }
    return false;
}

@compute @workgroup_size(64)
fn cullMain(@builtin(workgroup_id) group: vec3u, @builtin(local_invocation_index) lane: u32) {
    let index = (group.y * kMaxGroups + group.x) * 64u + lane;
    if (index >= params.itemCount) {
        return;
    }
    let item = loadItem(index);
    if (params.frustumTest != 0u) {
        let world = instances[item.slot].world;
        let center = (world * vec4f(vec3At(item.record, kBoundsCenter), 1.0)).xyz;
        let scale = max(length(world[0].xyz), max(length(world[1].xyz), length(world[2].xyz)));
        let radius = length(vec3At(item.record, kBoundsExtent)) * scale;
        if (outsideFrustum(center, radius)) {
            return;
        }
    }
    let first = atomicAdd(&counters.unitCount, item.unitCount);
    for (var unit = 0u; unit < item.unitCount; unit++) {
        units[first + unit] = vec2u(index, unit * kUnitTriangles);
    }
}

@compute @workgroup_size(1)
fn argsMain() {
    let count = atomicLoad(&counters.unitCount);
    rasterArguments = vec3u(min(count, kMaxGroups), max(1u, (count + kMaxGroups - 1u) / kMaxGroups),
                            1u);
}

// Sub-pixel precision of the snapped vertices, as the hardware's (8 bits).
const kSubpixels = 256.0;

fn toHardware(id: u32) {
    let slot = atomicAdd(&counters.hardwareVertices, 3u) / 3u;
    if (slot < params.hardwareCapacity) {
        hardwareList[slot] = id;
        atomicAdd(&counters.hardwareTriangles, 1u);
    } else {
        atomicAdd(&counters.hardwareOverflow, 1u);
    }
}

// The edge function of a -> b at p (twice the signed area), in fixed point.
fn edge(a: vec2i, b: vec2i, p: vec2i) -> i32 {
    return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
}

// With the triangle wound so that inside is positive (clockwise on the y-down screen): top edges
// run right along a row, left edges run up. Pixel centres on such an edge are inside, on the
// other edges outside, so a pixel shared by two triangles belongs to one.
fn topLeftBias(a: vec2i, b: vec2i) -> i32 {
    let d = b - a;
    return select(-1, 0, (d.y == 0 && d.x > 0) || d.y < 0);
}

fn windowPosition(clip: vec4f) -> vec3f {
    let ndc = clip.xyz / clip.w;
    let halfWidth = f32(params.viewportWidth) * 0.5;
    let halfHeight = f32(params.viewportHeight) * 0.5;
    return vec3f(ndc.x * halfWidth + (f32(params.viewportX) + halfWidth),
                 -ndc.y * halfHeight + (f32(params.viewportY) + halfHeight), ndc.z);
}

// Returns whether the compute raster drew the triangle (front-facing, on screen, not degenerate).
fn rasterTriangle(id: u32, item: Item, transform: Transform, triangle: u32) -> bool {
    let record = item.record;
    let c0 = clipPosition(worldPosition(record, transform, vertexIndex(record, triangle, 0u)));
    let c1 = clipPosition(worldPosition(record, transform, vertexIndex(record, triangle, 1u)));
    let c2 = clipPosition(worldPosition(record, transform, vertexIndex(record, triangle, 2u)));
    let xs = vec3f(c0.x, c1.x, c2.x);
    let ys = vec3f(c0.y, c1.y, c2.y);
    let zs = vec3f(c0.z, c1.z, c2.z);
    let ws = vec3f(c0.w, c1.w, c2.w);
    // Wholly outside one clip plane: nothing to draw anywhere.
    if (all(xs < -ws) || all(xs > ws) || all(ys < -ws) || all(ys > ws) || all(zs < vec3f(0.0)) ||
        all(zs > ws)) {
        return false;
    }
    let doubleSided = field(record, kDoubleSided) != 0u;
    if (any(zs < vec3f(0.0)) || any(zs > ws) || any(ws <= vec3f(0.0))) {
        // Crosses the near or far plane: the hardware clips. Facing from the homogeneous
        // determinant, which holds on either side of w = 0.
        let det = determinant(mat3x3f(c0.xyw, c1.xyw, c2.xyw));
        let front = (det > 0.0) != (item.mirrored != 0u);
        if (det != 0.0 && (front || doubleSided)) {
            toHardware(id);
        }
        return false;
    }
    let p0 = windowPosition(c0);
    let p1 = windowPosition(c1);
    let p2 = windowPosition(c2);
    let low = min(p0.xy, min(p1.xy, p2.xy));
    let high = max(p0.xy, max(p1.xy, p2.xy));
    if (any(high - low > vec2f(params.maxComputePixels))) {
        let det = determinant(mat3x3f(c0.xyw, c1.xyw, c2.xyw));
        let front = (det > 0.0) != (item.mirrored != 0u);
        if (det != 0.0 && (front || doubleSided)) {
            toHardware(id);
        }
        return false;
    }
    // Pixels whose centres may be covered (a pixel more each way: snapping moves vertices),
    // inside the viewport.
    let viewMin = vec2i(i32(params.viewportX), i32(params.viewportY));
    let viewMax = viewMin + vec2i(i32(params.viewportWidth), i32(params.viewportHeight)) - 1;
    let first = max(vec2i(floor(low - 0.5)), viewMin);
    let last = min(vec2i(ceil(high - 0.5)), viewMax);
    if (any(last < first)) {
        return false;
    }
    // Fixed point relative to the first pixel, so that products stay within 32 bits.
    let origin = vec2f(first) * kSubpixels;
    var v0 = vec2i(round(p0.xy * kSubpixels - origin));
    var v1 = vec2i(round(p1.xy * kSubpixels - origin));
    var v2 = vec2i(round(p2.xy * kSubpixels - origin));
    var z0 = p0.z;
    var z1 = p1.z;
    var z2 = p2.z;
    var area = edge(v0, v1, v2);
    if (area == 0) {
        return false;  // Degenerate once snapped: the hardware draws nothing either.
    }
    // Counter-clockwise in normalised device coordinates (front for glTF) turns clockwise on the
    // y-down screen: area < 0. Mirrored instances face the other way.
    let front = (area < 0) != (item.mirrored != 0u);
    if (!front && !doubleSided) {
        return false;
    }
    if (area < 0) {
        let swap = v1;
        v1 = v2;
        v2 = swap;
        let swapZ = z1;
        z1 = z2;
        z2 = swapZ;
        area = -area;
    }
    let bias0 = topLeftBias(v1, v2);
    let bias1 = topLeftBias(v2, v0);
    let bias2 = topLeftBias(v0, v1);
    let inverseArea = 1.0 / f32(area);
    let half = i32(kSubpixels) / 2;
    for (var y = first.y; y <= last.y; y++) {
        for (var x = first.x; x <= last.x; x++) {
            let p = (vec2i(x, y) - first) * i32(kSubpixels) + vec2i(half);
            let e0 = edge(v1, v2, p);
            let e1 = edge(v2, v0, p);
            let e2 = edge(v0, v1, p);
            if (e0 + bias0 < 0 || e1 + bias1 < 0 || e2 + bias2 < 0) {
                continue;
            }
            let depth = clamp((f32(e0) * z0 + f32(e1) * z1 + f32(e2) * z2) * inverseArea, 0.0,
                              1.0);
            let pixel = u32(y) * params.targetWidth + u32(x);
            atomicStoreMax(&visibility[pixel], vec2u(id, ~bitcast<u32>(depth)));
        }
    }
    return true;
}

var<workgroup> rasterised: atomic<u32>;
var<workgroup> unitCount: u32;

@compute @workgroup_size(64)
fn rasterMain(@builtin(workgroup_id) group: vec3u, @builtin(local_invocation_index) lane: u32) {
    let unitIndex = group.y * kMaxGroups + group.x;
    if (lane == 0u) {
        unitCount = atomicLoad(&counters.unitCount);
    }
    if (unitIndex >= workgroupUniformLoad(&unitCount)) {
        return;
    }
    let unit = units[unitIndex];
    let item = loadItem(unit.x);
    let transform = instances[item.slot];
    let triangleCount = field(item.record, kTriangleCount);
    var count = 0u;
    for (var k = 0u; k < kUnitTriangles / 64u; k++) {
        let local = k * 64u + lane;
        let triangle = unit.y + local;
        if (triangle < triangleCount &&
            rasterTriangle(unitIndex * kUnitTriangles + local, item, transform, triangle)) {
            count++;
        }
    }
    atomicAdd(&rasterised, count);
    workgroupBarrier();
    if (lane == 0u) {
        atomicAdd(&counters.computeTriangles, atomicLoad(&rasterised));
    }
}
