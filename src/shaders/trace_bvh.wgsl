// The closest hit of a ray in a scene's two levels of bounding volume hierarchies
// (src/trace/TraceScene.h): the objects' hierarchy, then, in each object the ray reaches, its
// primitive's hierarchy in object space. Both with a stack, the nearer child first; the CPU's
// trace::closestHit takes the same steps.
//
// The scene is bind group 1 of the shader that includes this file.

struct BvhNode {
    min: vec3f,
    first: u32,  // Interior: the first child (the second follows). Leaf: its first item.
    max: vec3f,
    count: u32,  // 0 for an interior node.
}

struct TraceTriangle {
    a: vec3f,
    index: u32,  // In its primitive.
    b: vec3f,
    padding0: u32,
    c: vec3f,
    padding1: u32,
}

struct TraceObject {
    worldToObject: mat4x4f,
    root: u32,  // In meshNodes.
    instance: u32,
    primitive: u32,
    material: u32,
}

@group(1) @binding(0) var<storage, read> meshNodes: array<BvhNode>;
@group(1) @binding(1) var<storage, read> traceTriangles: array<TraceTriangle>;
@group(1) @binding(2) var<storage, read> objectNodes: array<BvhNode>;
@group(1) @binding(3) var<storage, read> traceObjects: array<TraceObject>;

const kNoObject = 0xffffffffu;
// Embree's builds are at most 64 deep (trace::BvhBuilder), and each step pushes at most two.
const kTraceStackSize = 66u;

struct TraceHit {
    t: f32,
    object: u32,    // kNoObject: the ray hit nothing before its tMax.
    triangle: u32,  // In traceTriangles.
    barycentric: vec2f,  // Of corners b and c.
}

// Where the ray enters the node's box, or -1 when it misses it within [tMin, tMax].
fn boxEntry(node: BvhNode, origin: vec3f, inverseDirection: vec3f, tMin: f32, tMax: f32) -> f32 {
    let t0 = (node.min - origin) * inverseDirection;
    let t1 = (node.max - origin) * inverseDirection;
    let near = min(t0, t1);
    let far = max(t0, t1);
    let enter = max(max(max(near.x, near.y), near.z), tMin);
    let exit = min(min(min(far.x, far.y), far.z), tMax);
    return select(enter, -1.0, enter > exit);
}

// Moller-Trumbore, both faces: (t, u, v), t = -1 when the ray misses within (tMin, tMax).
fn intersectTriangle(origin: vec3f, direction: vec3f, triangle: TraceTriangle, tMin: f32,
                     tMax: f32) -> vec3f {
    let miss = vec3f(-1.0, 0.0, 0.0);
    let edge1 = triangle.b - triangle.a;
    let edge2 = triangle.c - triangle.a;
    let p = cross(direction, edge2);
    let determinant = dot(edge1, p);
    if (determinant == 0.0) {
        return miss;
    }
    let inverse = 1.0 / determinant;
    let s = origin - triangle.a;
    let u = dot(s, p) * inverse;
    if (u < 0.0 || u > 1.0) {
        return miss;
    }
    let q = cross(s, edge1);
    let v = dot(direction, q) * inverse;
    if (v < 0.0 || u + v > 1.0) {
        return miss;
    }
    let t = dot(edge2, q) * inverse;
    if (!(t > tMin && t < tMax)) {
        return miss;
    }
    return vec3f(t, u, v);
}

// Pushes the children at `first` whose boxes the ray enters (entry distances `near` and `far`,
// -1 for a miss), the nearer last so that it is visited first.
fn pushChildren(stack: ptr<function, array<u32, kTraceStackSize>>, size: ptr<function, u32>,
                first: u32, near: f32, far: f32) {
    if (near >= 0.0 && far >= 0.0) {
        let firstNearer = near <= far;
        (*stack)[*size] = select(first, first + 1u, firstNearer);
        (*stack)[*size + 1u] = select(first + 1u, first, firstNearer);
        *size += 2u;
    } else if (near >= 0.0) {
        (*stack)[*size] = first;
        *size += 1u;
    } else if (far >= 0.0) {
        (*stack)[*size] = first + 1u;
        *size += 1u;
    }
}

// The primitive's triangles from `root`, in object space: shortens hit.t and sets its triangle
// and barycentric coordinates when one is nearer.
fn traceMesh(root: u32, origin: vec3f, direction: vec3f, tMin: f32, hit: ptr<function, TraceHit>)
    -> bool {
    let inverse = 1.0 / direction;
    var found = false;
    var stack: array<u32, kTraceStackSize>;
    var size = 0u;
    if (boxEntry(meshNodes[root], origin, inverse, tMin, (*hit).t) >= 0.0) {
        stack[0] = root;
        size = 1u;
    }
    while (size > 0u) {
        size -= 1u;
        let node = meshNodes[stack[size]];
        if (node.count != 0u) {
            for (var i = node.first; i < node.first + node.count; i += 1u) {
                let tuv = intersectTriangle(origin, direction, traceTriangles[i], tMin, (*hit).t);
                if (tuv.x >= 0.0) {
                    (*hit).t = tuv.x;
                    (*hit).triangle = i;
                    (*hit).barycentric = tuv.yz;
                    found = true;
                }
            }
            continue;
        }
        pushChildren(&stack, &size, node.first,
                     boxEntry(meshNodes[node.first], origin, inverse, tMin, (*hit).t),
                     boxEntry(meshNodes[node.first + 1u], origin, inverse, tMin, (*hit).t));
    }
    return found;
}

// The nearest surface along origin + t direction for t in (tMin, tMax). The direction need not
// be normalised: t is in its units, in world and object space alike.
fn closestHit(origin: vec3f, direction: vec3f, tMin: f32, tMax: f32) -> TraceHit {
    var hit = TraceHit(tMax, kNoObject, 0u, vec2f(0.0));
    // A scene without objects has one zeroed node: an interior node cannot name itself as its
    // first child, so that marks the empty tree.
    if (objectNodes[0].count == 0u && objectNodes[0].first == 0u) {
        return hit;
    }
    let inverse = 1.0 / direction;
    var stack: array<u32, kTraceStackSize>;
    var size = 0u;
    if (boxEntry(objectNodes[0], origin, inverse, tMin, hit.t) >= 0.0) {
        stack[0] = 0u;
        size = 1u;
    }
    while (size > 0u) {
        size -= 1u;
        let node = objectNodes[stack[size]];
        if (node.count != 0u) {
            for (var o = node.first; o < node.first + node.count; o += 1u) {
                let object = traceObjects[o];
                let localOrigin = (object.worldToObject * vec4f(origin, 1.0)).xyz;
                let localDirection = (object.worldToObject * vec4f(direction, 0.0)).xyz;
                if (traceMesh(object.root, localOrigin, localDirection, tMin, &hit)) {
                    hit.object = o;
                }
            }
            continue;
        }
        pushChildren(&stack, &size, node.first,
                     boxEntry(objectNodes[node.first], origin, inverse, tMin, hit.t),
                     boxEntry(objectNodes[node.first + 1u], origin, inverse, tMin, hit.t));
    }
    return hit;
}
