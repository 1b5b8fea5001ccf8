// Shared by the environment compute shaders (render/Environment.cpp): cube and panorama
// directions, the low-discrepancy sequence and the sampling of the GGX and cosine lobes.

const kPi = 3.14159265358979;

// The direction through `uv` (0..1 across a face, v growing downwards like texture rows) on
// `face` of a cube map, in WebGPU's (= Vulkan's and D3D's) convention: faces +X, -X, +Y, -Y,
// +Z, -Z, and a direction d is looked up on the face of its major axis ma at
// u = (sc / |ma| + 1) / 2, v = (tc / |ma| + 1) / 2 with (sc, tc) = (-z, -y) on +X, (z, -y) on
// -X, (x, z) on +Y, (x, -z) on -Y, (x, -y) on +Z, (-x, -y) on -Z. This is the inverse.
fn cubeDirection(face: u32, uv: vec2f) -> vec3f {
    let s = uv.x * 2.0 - 1.0;
    let t = uv.y * 2.0 - 1.0;
    var d: vec3f;
    switch face {
        case 0u: { d = vec3f(1.0, -t, -s); }
        case 1u: { d = vec3f(-1.0, -t, s); }
        case 2u: { d = vec3f(s, 1.0, t); }
        case 3u: { d = vec3f(s, -1.0, -t); }
        case 4u: { d = vec3f(s, -t, 1.0); }
        default: { d = vec3f(-s, -t, -1.0); }
    }
    return normalize(d);
}

// The centre of texel `texel` of a face `size` texels wide.
fn texelDirection(face: u32, texel: vec2u, size: u32) -> vec3f {
    return cubeDirection(face, (vec2f(texel) + 0.5) / f32(size));
}

// Point i of n of the Hammersley set in [0,1)^2.
fn hammersley(i: u32, n: u32) -> vec2f {
    return vec2f(f32(i) / f32(n), f32(reverseBits(i)) * 2.3283064365386963e-10);
}

// Maps a tangent-space vector (z along n) to world space. Any frame around n will do: the
// integrals are rotation invariant about n.
fn tangentToWorld(v: vec3f, n: vec3f) -> vec3f {
    let up = select(vec3f(1.0, 0.0, 0.0), vec3f(0.0, 0.0, 1.0), abs(n.z) < 0.999);
    let tangent = normalize(cross(up, n));
    let bitangent = cross(n, tangent);
    return tangent * v.x + bitangent * v.y + n * v.z;
}

// A GGX-distributed half vector in tangent space (pdf D(h) * NdotH), alpha = roughness^2.
fn sampleGgx(xi: vec2f, alpha: f32) -> vec3f {
    let a2 = alpha * alpha;
    let cosTheta = sqrt((1.0 - xi.x) / (1.0 + (a2 - 1.0) * xi.x));
    let sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
    let phi = 2.0 * kPi * xi.y;
    return vec3f(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
}

// The GGX normal distribution D(h), alpha = roughness^2.
fn distributionGgx(nDotH: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let f = nDotH * nDotH * (a2 - 1.0) + 1.0;
    return a2 / (kPi * f * f);
}

// The source mip whose texels cover about the solid angle one sample stands for (filtered
// importance sampling, Krivanek and Colbert, GPU Gems 3 chapter 20). The +1 biases towards the
// blurrier level, which hides the sample pattern at the cost of a little extra blur.
fn sourceLod(pdf: f32, sampleCount: u32, texelSolidAngle: f32, maxLod: f32) -> f32 {
    let sampleSolidAngle = 1.0 / (f32(sampleCount) * pdf + 1e-6);
    return clamp(0.5 * log2(sampleSolidAngle / texelSolidAngle) + 1.0, 0.0, maxLod);
}
