#include "tone_map.wgsl"

// Group 0, bindings 1..6: how the scene is lit and displayed. Shared by every pipeline (BindGroupLayouts::frame);
// only the physically based mesh shader and the environment background read them. Everything
// here changes through buffers and in-place texture writes, so recorded bundles stay valid.

struct Lighting {
    // World direction -> environment direction (a rotation about +Y), as three columns.
    environmentRotation: mat3x3f,
    environmentIntensity: f32,
    // Mip levels of the specular cube: roughness r samples level r * (levels - 1).
    specularLevels: f32,
    lightCount: u32,
    imageBasedLighting: u32,  // 0: the environment lights nothing (it may still be drawn).
    // What the mesh shader writes (LightingDebug in C++): 0 the shaded colour, 1 base colour,
    // 2 shading normal, 3 metallic, 4 roughness, 5 occlusion, 6 emissive.
    debugChannel: u32,
    // The display transform (tone_map.wgsl), applied by displayColor when displayMapped is 1:
    // the scene renders straight into the sRGB output. 0: the target is linear HDR and a later
    // pass maps it (tone_mapping.wgsl).
    exposure: f32,
    toneMapping: u32,
    displayMapped: u32,
}

// KHR_lights_punctual in world space (LightBuffer in C++).
struct PunctualLight {
    position: vec3f,
    range: f32,       // 0: unlimited.
    direction: vec3f, // Where the light shines (normalised).
    kind: u32,        // 0 directional, 1 point, 2 spot.
    color: vec3f,
    intensity: f32,
    innerConeCos: f32,
    outerConeCos: f32,
    padding0: f32,
    padding1: f32,
}

@group(0) @binding(1) var<uniform> lighting: Lighting;
@group(0) @binding(2) var<storage, read> lights: array<PunctualLight>;
@group(0) @binding(3) var specularEnvironment: texture_cube<f32>;
@group(0) @binding(4) var irradianceEnvironment: texture_cube<f32>;
@group(0) @binding(5) var brdfLut: texture_2d<f32>;
@group(0) @binding(6) var environmentSampler: sampler;

fn environmentDirection(worldDirection: vec3f) -> vec3f {
    return lighting.environmentRotation * worldDirection;
}

// What a scene shader writes for a linear colour: the display colour when the scene renders
// straight into the output, the linear colour itself for an HDR target.
fn displayColor(color: vec4f) -> vec4f {
    if (lighting.displayMapped == 0u) {
        return color;
    }
    return vec4f(toneMap(color.rgb, lighting.exposure, lighting.toneMapping), color.a);
}
