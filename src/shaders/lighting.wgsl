// The case study's simple directional light plus ambient term. Zero-length normals (points and
// lines without NORMAL) are drawn unlit.
const kLightDirection = vec3f(0.25, 0.5, 1.0);
const kAmbient = vec3f(0.1);

fn shade(baseColor: vec3f, normal: vec3f) -> vec3f {
    if (dot(normal, normal) < 1e-12) {
        return baseColor;
    }
    let n = normalize(normal);
    let nDotL = max(dot(n, normalize(kLightDirection)), 0.0);
    return baseColor * kAmbient + baseColor * nDotL;
}
