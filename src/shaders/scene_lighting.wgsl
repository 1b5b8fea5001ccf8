#include "tone_map.wgsl"
#include "environment_atlas.wgsl"

// Group 0, bindings 1..4: how the scene is lit and displayed. Shared by every pipeline (BindGroupLayouts::frame);
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
    atlas: EnvironmentAtlasLayout,
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
// The prefiltered specular levels, the irradiance and the BRDF table (environment_atlas.wgsl).
@group(0) @binding(3) var environmentAtlas: texture_2d<f32>;
@group(0) @binding(4) var environmentSampler: sampler;

fn environmentDirection(worldDirection: vec3f) -> vec3f {
    return lighting.environmentRotation * worldDirection;
}

// Radiance toward a world direction, prefiltered for the GGX lobe of specular level `level`
// (roughness level / (levels - 1)); fractional levels blend the two nearest, as trilinear
// filtering between mips would.
fn environmentRadiance(worldDirection: vec3f, level: f32) -> vec3f {
    let lookup = cubeFaceUv(environmentDirection(worldDirection));
    let clamped = clamp(level, 0.0, lighting.specularLevels - 1.0);
    let lower = u32(clamped);
    let upper = min(lower + 1u, u32(lighting.specularLevels) - 1u);
    let inverseSize = lighting.atlas.inverseSize;
    let a = textureSampleLevel(environmentAtlas, environmentSampler,
                               atlasCubeCoordinates(lighting.atlas.specular[lower], lookup.face,
                                                    lookup.uv, inverseSize),
                               0.0).rgb;
    let b = textureSampleLevel(environmentAtlas, environmentSampler,
                               atlasCubeCoordinates(lighting.atlas.specular[upper], lookup.face,
                                                    lookup.uv, inverseSize),
                               0.0).rgb;
    return mix(a, b, clamped - f32(lower)) * lighting.environmentIntensity;
}

// Cosine-weighted average radiance around a world normal.
fn environmentIrradiance(worldNormal: vec3f) -> vec3f {
    let lookup = cubeFaceUv(environmentDirection(worldNormal));
    return textureSampleLevel(environmentAtlas, environmentSampler,
                              atlasCubeCoordinates(lighting.atlas.irradiance, lookup.face,
                                                   lookup.uv, lighting.atlas.inverseSize),
                              0.0).rgb *
           lighting.environmentIntensity;
}

// The split-sum table at (NdotV, perceptual roughness): F0 scale, bias, sheen albedo.
fn brdfLutAt(nDotV: f32, roughness: f32) -> vec3f {
    let uv = clamp(vec2f(nDotV, roughness), vec2f(0.0), vec2f(1.0));
    return textureSampleLevel(environmentAtlas, environmentSampler,
                              atlasTableCoordinates(lighting.atlas.brdf, uv,
                                                    lighting.atlas.inverseSize),
                              0.0).rgb;
}

// What a scene shader writes for a linear colour: the display colour when the scene renders
// straight into the output, the linear colour itself for an HDR target.
fn displayColor(color: vec4f) -> vec4f {
    if (lighting.displayMapped == 0u) {
        return color;
    }
    return vec4f(toneMap(color.rgb, lighting.exposure, lighting.toneMapping), color.a);
}
