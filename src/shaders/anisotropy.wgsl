// KHR_materials_anisotropy, as the Khronos Sample Renderer shades it: the GGX lobe gets two
// roughnesses, the material's across the anisotropy direction and a rougher one along it
// (mix(alpha, 1, strength^2)); punctual lights use the anisotropic GGX distribution and
// visibility, and image-based light is looked up around a normal bent towards the direction
// across the anisotropy, which stretches reflections along it. Needs brdf.wgsl, material.wgsl
// and surface_shading.wgsl's SurfaceFrame.

struct Anisotropy {
    tangent: vec3f,    // The anisotropy direction in world space (in the tangent plane).
    bitangent: vec3f,  // Across it: cross(geometric normal, tangent).
    strength: f32,     // 0..1.
}

// The direction and strength at a surface point: the tangent turned by the material's rotation
// (material.anisotropy.xy: its cosine and sine), or with a texture its red-green direction
// (-1..1) turned by it, the blue channel scaling the strength (material.anisotropy.z).
fn anisotropyAt(surface: SurfaceFrame, sampled: vec3f, textured: bool) -> Anisotropy {
    var direction = vec2f(1.0, 0.0);
    var strength = 1.0;
    if (textured) {
        direction = sampled.xy * 2.0 - 1.0;
        strength = sampled.z;
    }
    let rotation = material.anisotropy.xy;
    direction = mat2x2f(rotation.x, rotation.y, -rotation.y, rotation.x) * direction;
    var result: Anisotropy;
    let planar = select(vec3f(1.0, 0.0, 0.0), normalize(vec3f(direction, 0.0)),
                        dot(direction, direction) > 1e-12);
    result.tangent = mat3x3f(surface.tangent, surface.bitangent, surface.normal) * planar;
    result.bitangent = cross(surface.geometric, result.tangent);
    result.strength = clamp(material.anisotropy.z * strength, 0.0, 1.0);
    return result;
}

// The normal image-based specular light is reflected about: bent from `n` towards the normal
// of the plane holding the anisotropy's bitangent, the more so the stronger and smoother.
fn anisotropicBentNormal(n: vec3f, v: vec3f, roughness: f32, anisotropy: Anisotropy) -> vec3f {
    let b = anisotropy.bitangent;
    let across = cross(cross(b, v), b);
    let bend = 1.0 - anisotropy.strength * (1.0 - roughness);
    let bend2 = bend * bend;
    return normalize(mix(across, n, bend2 * bend2));
}

// The anisotropic GGX specular lobe (distribution times visibility) for light `l`.
fn specularGgxAnisotropic(alpha: f32, anisotropy: Anisotropy, n: vec3f, v: vec3f, l: vec3f,
                          h: vec3f) -> f32 {
    let t = anisotropy.tangent;
    let b = anisotropy.bitangent;
    let alphaT = mix(alpha, 1.0, anisotropy.strength * anisotropy.strength);
    let alphaB = clamp(alpha, 0.001, 1.0);
    let nDotL = clamp(dot(n, l), 0.0, 1.0);
    let nDotH = clamp(dot(n, h), 0.001, 1.0);
    let nDotV = dot(n, v);

    let viewTerm = nDotL * length(vec3f(alphaT * dot(t, v), alphaB * dot(b, v), nDotV));
    let lightTerm = nDotV * length(vec3f(alphaT * dot(t, l), alphaB * dot(b, l), nDotL));
    let visibility = clamp(0.5 / (viewTerm + lightTerm), 0.0, 1.0);

    let a2 = alphaT * alphaB;
    let f = vec3f(alphaB * dot(t, h), alphaT * dot(b, h), a2 * nDotH);
    let w2 = a2 / dot(f, f);
    let distribution = a2 * w2 * w2 / kPi;
    return visibility * distribution;
}
