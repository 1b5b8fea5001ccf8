// GPU animation, pass 1 (GpuAnimation): samples the channels that drive each animated node at
// this frame's time and writes the node's local matrix (T * R * S) and its morph weights. One
// thread per node that any animation of the file drives; properties no selected channel drives
// keep their rest value, and a node no selected channel drives keeps its rest matrix. Sampling
// follows scene::sampleAnimation (glTF 2.0 appendix C): STEP holds the key at or before t,
// LINEAR interpolates (rotations by normalised shortest-path slerp), CUBICSPLINE is the Hermite
// spline with tangents scaled by the key interval; before the first key the first value, after
// the last key the last value.

const kNone: u32 = 0xffffffffu;
const kStep: u32 = 0u;
const kLinear: u32 = 1u;
const kCubicSpline: u32 = 2u;

struct Sampler {
    timesOffset: u32,    // Into keyframes: keyCount key times, strictly increasing.
    keyCount: u32,
    valuesOffset: u32,   // Into keyframes: per key `components` values (CUBICSPLINE: in-tangent,
                         // value, out-tangent).
    components: u32,
    interpolation: u32,
    animation: u32,      // Index into animations.
    pad0: u32,
    pad1: u32,
}

struct AnimatedNode {
    restLocal: mat4x4f,
    translation: vec4f,  // Rest pose, xyz.
    rotation: vec4f,     // Rest pose, x y z w.
    scale: vec4f,        // Rest pose, xyz.
    node: u32,
    weightOffset: u32,   // Into weights (kNone: no morph weights).
    weightCount: u32,
    restWeights: u32,    // Into keyframes: the node's rest weights.
}

@group(0) @binding(0) var<storage, read> keyframes: array<f32>;
@group(0) @binding(1) var<storage, read> samplers: array<Sampler>;
// Animations share clocks (one per distinct duration), so that the CPU writes per frame one
// float per clock, however many animations (a crowd's characters) play with their own offsets.
struct AnimationClock {
    clock: u32,           // Index into clocks (after its header).
    offset: f32,          // Animation::timeOffset (playing clamped).
    wrappedOffset: f32,   // The offset wrapped into [0, end) (playing in a loop).
    end: f32,             // The animation's duration (0: never wraps).
}
// clocks[0]: 1 when playing in a loop, else 0; clocks[1 + c]: clock c's time this frame, already
// wrapped into [0, end) by the CPU when looping.
@group(0) @binding(2) var<storage, read> clocks: array<f32>;
@group(0) @binding(7) var<storage, read> animations: array<AnimationClock>;
@group(0) @binding(3) var<storage, read> nodes: array<AnimatedNode>;
// Per animated node, the sampler driving translation, rotation, scale and weights (kNone: none).
@group(0) @binding(4) var<storage, read> nodeChannels: array<vec4u>;
@group(0) @binding(5) var<storage, read_write> locals: array<mat4x4f>;
@group(0) @binding(6) var<storage, read_write> weights: array<f32>;

override kWorkgroupSize: u32 = 64;

// Where t falls: key `k`, and, between keys, the fraction `u` of the interval of length
// `interval` towards key k + 1 (held: the value of key k as it is).
struct Key {
    k: u32,
    u: f32,
    interval: f32,
    held: bool,
}

fn findKey(s: Sampler, time: f32) -> Key {
    let last = s.keyCount - 1u;
    if (s.keyCount == 1u || !(time > keyframes[s.timesOffset])) {
        return Key(0u, 0.0, 0.0, true);
    }
    if (time >= keyframes[s.timesOffset + last]) {
        return Key(last, 0.0, 0.0, true);
    }
    // Binary search: times[lo] <= time < times[hi].
    var lo = 0u;
    var hi = last;
    while (hi - lo > 1u) {
        let mid = (lo + hi) / 2u;
        if (keyframes[s.timesOffset + mid] <= time) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    if (s.interpolation == kStep) {
        return Key(lo, 0.0, 0.0, true);
    }
    let t0 = keyframes[s.timesOffset + lo];
    let interval = keyframes[s.timesOffset + lo + 1u] - t0;
    return Key(lo, clamp((time - t0) / interval, 0.0, 1.0), interval, false);
}

// Component c of key k's value (CUBICSPLINE: part 0 in-tangent, 1 value, 2 out-tangent).
fn keyValue(s: Sampler, k: u32, part: u32, c: u32) -> f32 {
    if (s.interpolation == kCubicSpline) {
        return keyframes[s.valuesOffset + (k * 3u + part) * s.components + c];
    }
    return keyframes[s.valuesOffset + k * s.components + c];
}

// Component c of the sampler's output at `key`, componentwise (not for slerped rotations).
fn sampleComponent(s: Sampler, key: Key, c: u32) -> f32 {
    if (key.held) {
        return keyValue(s, key.k, 1u, c);
    }
    if (s.interpolation == kLinear) {
        let a = keyValue(s, key.k, 1u, c);
        let b = keyValue(s, key.k + 1u, 1u, c);
        return a + (b - a) * key.u;
    }
    let u = key.u;
    let u2 = u * u;
    let u3 = u2 * u;
    let h00 = 2.0 * u3 - 3.0 * u2 + 1.0;
    let h10 = u3 - 2.0 * u2 + u;
    let h01 = -2.0 * u3 + 3.0 * u2;
    let h11 = u3 - u2;
    return h00 * keyValue(s, key.k, 1u, c) + h10 * key.interval * keyValue(s, key.k, 2u, c) +
           h01 * keyValue(s, key.k + 1u, 1u, c) + h11 * key.interval * keyValue(s, key.k + 1u, 0u, c);
}

fn sampleVec3(index: u32, time: f32) -> vec3f {
    let s = samplers[index];
    let key = findKey(s, time);
    return vec3f(sampleComponent(s, key, 0u), sampleComponent(s, key, 1u),
                 sampleComponent(s, key, 2u));
}

fn keyQuaternion(s: Sampler, k: u32) -> vec4f {
    return vec4f(keyValue(s, k, 1u, 0u), keyValue(s, k, 1u, 1u), keyValue(s, k, 1u, 2u),
                 keyValue(s, k, 1u, 3u));
}

fn normalizeQuaternion(q: vec4f) -> vec4f {
    let len = sqrt(dot(q, q));
    if (len > 0.0 && len <= 3.4028234e38) {
        return q / len;
    }
    return vec4f(0.0, 0.0, 0.0, 1.0);
}

fn sampleRotation(index: u32, time: f32) -> vec4f {
    let s = samplers[index];
    let key = findKey(s, time);
    var q: vec4f;
    if (key.held) {
        q = keyQuaternion(s, key.k);
    } else if (s.interpolation == kLinear) {
        // Shortest-path slerp; nearly parallel quaternions interpolate linearly.
        let a = keyQuaternion(s, key.k);
        let b = keyQuaternion(s, key.k + 1u);
        var d = dot(a, b);
        let flip = select(1.0, -1.0, d < 0.0);
        d = abs(d);
        var wa = 1.0 - key.u;
        var wb = key.u;
        if (d < 0.9995) {
            let theta = acos(min(d, 1.0));
            let sine = sin(theta);
            wa = sin((1.0 - key.u) * theta) / sine;
            wb = sin(key.u * theta) / sine;
        }
        q = wa * a + flip * wb * b;
    } else {
        q = vec4f(sampleComponent(s, key, 0u), sampleComponent(s, key, 1u),
                  sampleComponent(s, key, 2u), sampleComponent(s, key, 3u));
    }
    return normalizeQuaternion(q);
}

// As scene::AnimationPlayer: (t + offset) mod end when looping, t + offset otherwise; the CPU
// wrapped t, and both terms lie in [0, end), so one subtraction wraps their sum.
fn timeOf(index: u32) -> f32 {
    let a = animations[samplers[index].animation];
    let time = clocks[1u + a.clock];
    if (clocks[0] != 0.0 && a.end > 0.0) {
        let wrapped = time + a.wrappedOffset;
        return select(wrapped, wrapped - a.end, wrapped >= a.end);
    }
    return time + a.offset;
}

// translate(t) * mat4_cast(normalize(q)) * scale(s), as scene::composeTrs.
fn composeTrs(t: vec3f, rotation: vec4f, s: vec3f) -> mat4x4f {
    var r = mat3x3f(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0);
    let len = sqrt(dot(rotation, rotation));
    if (len > 0.0) {
        let q = rotation / len;
        let xx = q.x * q.x;
        let yy = q.y * q.y;
        let zz = q.z * q.z;
        let xz = q.x * q.z;
        let xy = q.x * q.y;
        let yz = q.y * q.z;
        let wx = q.w * q.x;
        let wy = q.w * q.y;
        let wz = q.w * q.z;
        r = mat3x3f(1.0 - 2.0 * (yy + zz), 2.0 * (xy + wz), 2.0 * (xz - wy),
                    2.0 * (xy - wz), 1.0 - 2.0 * (xx + zz), 2.0 * (yz + wx),
                    2.0 * (xz + wy), 2.0 * (yz - wx), 1.0 - 2.0 * (xx + yy));
    }
    return mat4x4f(vec4f(r[0] * s.x, 0.0), vec4f(r[1] * s.y, 0.0), vec4f(r[2] * s.z, 0.0),
                   vec4f(t, 1.0));
}

@compute @workgroup_size(kWorkgroupSize)
fn sampleNodes(@builtin(global_invocation_id) id: vec3u) {
    if (id.x >= arrayLength(&nodes)) {
        return;
    }
    let node = nodes[id.x];
    let channels = nodeChannels[id.x];
    if (channels.x == kNone && channels.y == kNone && channels.z == kNone) {
        locals[node.node] = node.restLocal;
    } else {
        var t = node.translation.xyz;
        var r = node.rotation;
        var s = node.scale.xyz;
        if (channels.x != kNone) {
            t = sampleVec3(channels.x, timeOf(channels.x));
        }
        if (channels.y != kNone) {
            r = sampleRotation(channels.y, timeOf(channels.y));
        }
        if (channels.z != kNone) {
            s = sampleVec3(channels.z, timeOf(channels.z));
        }
        locals[node.node] = composeTrs(t, r, s);
    }
    if (node.weightOffset == kNone) {
        return;
    }
    if (channels.w == kNone) {
        for (var c = 0u; c < node.weightCount; c++) {
            weights[node.weightOffset + c] = keyframes[node.restWeights + c];
        }
        return;
    }
    let s = samplers[channels.w];
    let key = findKey(s, timeOf(channels.w));
    for (var c = 0u; c < node.weightCount; c++) {
        weights[node.weightOffset + c] = select(0.0, sampleComponent(s, key, c), c < s.components);
    }
}
