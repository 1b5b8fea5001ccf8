// KHR_materials_transmission, KHR_materials_volume and KHR_materials_dispersion, as the Khronos
// Sample Renderer shades them: light from behind a transmissive surface is the scene drawn
// without transmissive surfaces (the transmission pass's copy, render/TransmissionPass.h),
// sampled where the refracted ray leaves the volume (thin-walled without a volume: straight
// through) and blurred by a mip level that grows with roughness; a volume absorbs along the ray
// (Beer-Lambert). Needs frame.wgsl, scene_lighting.wgsl (its sampler) and brdf.wgsl.

// The scene behind transmissive surfaces: linear colour with a full mip chain (a 1-pixel
// placeholder in scenes without transmission, never read there).
@group(0) @binding(5) var transmissionBackground: texture_2d<f32>;

// What shadeSurface knows of a transmissive material at one point.
struct TransmissiveSurface {
    factor: f32,               // transmissionFactor times its texture.
    thickness: f32,            // In the mesh's units; 0: thin-walled.
    ior: f32,                  // 0: infinite.
    dispersion: f32,
    attenuationDistance: f32,  // 0: no absorption.
    attenuationColor: vec3f,
    modelScale: vec3f,         // Lengths of the world matrix's axes (the thickness is local).
}

// Roughness as the refraction blurs it: none at IOR 1, fully from IOR 1.5 up.
fn iorRoughness(roughness: f32, ior: f32) -> f32 {
    let effectiveIor = select(ior, 1e4, ior == 0.0);
    return roughness * clamp(effectiveIor * 2.0 - 2.0, 0.0, 1.0);
}

// From the surface point to where the refracted view ray leaves the volume.
fn volumeTransmissionRay(n: vec3f, v: vec3f, thickness: f32, ior: f32, modelScale: vec3f) -> vec3f {
    let eta = select(1.0 / ior, 0.0, ior == 0.0);
    let refracted = refract(-v, n, eta);
    let direction = select(-n, normalize(refracted), dot(refracted, refracted) > 1e-12);
    return direction * thickness * modelScale;
}

// Beer-Lambert: white light turns attenuationColor after attenuationDistance.
fn volumeAttenuation(radiance: vec3f, distance: f32, color: vec3f, attenuationDistance: f32) -> vec3f {
    if (attenuationDistance <= 0.0) {
        return radiance;
    }
    return pow(color, vec3f(distance / attenuationDistance)) * radiance;
}

// The background seen through world point `exit`, blurred for `roughness` at `ior`.
fn transmissionSample(exit: vec3f, roughness: f32, ior: f32) -> vec3f {
    let clip = frame.projection * frame.view * vec4f(exit, 1.0);
    let ndc = clip.xy / clip.w;
    let viewUv = vec2f(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5);
    let uv = frame.viewRect.xy + viewUv * frame.viewRect.zw;
    let size = vec2f(textureDimensions(transmissionBackground));
    let level = log2(size.x) * iorRoughness(roughness, ior);
    return textureSampleLevel(transmissionBackground, environmentSampler, uv, level).rgb;
}

// The light a transmissive surface lets through towards the viewer, before the Fresnel split
// with the specular reflection (which shadeSurface applies, as to the diffuse layer it
// replaces). With dispersion, each channel refracts with its own IOR.
fn volumeRefraction(surface: TransmissiveSurface, n: vec3f, v: vec3f, position: vec3f,
                    roughness: f32, baseColor: vec3f) -> vec3f {
    var transmitted: vec3f;
    var rayLength: f32;
    if (surface.dispersion > 0.0 && surface.ior > 0.0) {
        let halfSpread = (surface.ior - 1.0) * 0.025 * surface.dispersion;
        let iors = vec3f(surface.ior - halfSpread, surface.ior, surface.ior + halfSpread);
        for (var channel = 0; channel < 3; channel++) {
            let ray = volumeTransmissionRay(n, v, surface.thickness, iors[channel],
                                            surface.modelScale);
            rayLength = length(ray);
            transmitted[channel] =
                transmissionSample(position + ray, roughness, iors[channel])[channel];
        }
    } else {
        let ray = volumeTransmissionRay(n, v, surface.thickness, surface.ior, surface.modelScale);
        rayLength = length(ray);
        transmitted = transmissionSample(position + ray, roughness, surface.ior);
    }
    return volumeAttenuation(transmitted, rayLength, surface.attenuationColor,
                             surface.attenuationDistance) * baseColor;
}

// A punctual light seen through the surface: the GGX lobe around the refracted direction
// (mirrored through the surface), with the light taken from where the ray leaves the volume.
fn punctualTransmission(surface: TransmissiveSurface, light: PunctualLight, n: vec3f, v: vec3f,
                        position: vec3f, alphaRoughness: f32, baseColor: vec3f) -> vec3f {
    let ray = volumeTransmissionRay(n, v, surface.thickness, surface.ior, surface.modelScale);
    let incoming = incomingLight(light, position + ray);
    let l = incoming.direction;
    let mirrored = normalize(l - 2.0 * n * dot(l, n));
    let h = normalize(mirrored + v);
    let alpha = max(iorRoughness(alphaRoughness, surface.ior), 2e-3);
    let lobe = distributionGgx(clamp(dot(n, h), 0.0, 1.0), alpha) *
               visibilityGgx(clamp(dot(n, mirrored), 0.0, 1.0), clamp(dot(n, v), 0.0, 1.0), alpha);
    return volumeAttenuation(incoming.radiance * baseColor * lobe, length(ray),
                             surface.attenuationColor, surface.attenuationDistance);
}
