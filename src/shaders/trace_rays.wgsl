// One thread per ray: the closest hit of each (trace::RayQueries, for tests and tools).

#include "trace_bvh.wgsl"

struct QueryRay {
    origin: vec3f,
    tMin: f32,
    direction: vec3f,
    tMax: f32,
}

@group(0) @binding(0) var<storage, read> rays: array<QueryRay>;
@group(0) @binding(1) var<storage, read_write> hits: array<TraceHit>;

@compute @workgroup_size(64)
fn closestHits(@builtin(global_invocation_id) id: vec3u) {
    if (id.x >= arrayLength(&rays)) {
        return;
    }
    let ray = rays[id.x];
    hits[id.x] = closestHit(ray.origin, ray.direction, ray.tMin, ray.tMax);
}
