// Group 2: one glTF material (MaterialResources in C++). The uniform holds every factor and,
// for each of the twelve texture slots, the texCoord set and KHR_texture_transform; with
// MATERIAL_TEXTURES each slot has its own sampler (the glTF sampler of its texture) and texture
// (a 1-pixel default when the material has none: white, so that factors multiply through
// unchanged). Materials with no texture at all bind the uniform only and read white.
//
// Written by hand to match C++: the slot table (render/MaterialSlots.h: names, bindings, slot
// indices), MaterialUniform and the kMaterial*/kModel* values (render/MaterialUniform.h).
// tests/unit/render/MaterialWgslTest.cpp fails when they disagree.

// Rows of the slot's 2x3 texture transform applied to (u, v, 1); row0.w: 1 reads TEXCOORD_1.
struct TextureSlot {
    row0: vec4f,
    row1: vec4f,
}

struct Material {
    baseColorFactor: vec4f,
    emissive: vec4f,            // rgb: emissiveFactor * KHR_materials_emissive_strength.
    metallicRoughness: vec4f,   // metallic, roughness, normal scale, occlusion strength.
    alpha: vec4f,               // alphaCutoff (MASK), 1 for BLEND, IOR (0: infinite), unused.
    specular: vec4f,            // KHR_materials_specular: rgb colour factor, a: factor.
    clearcoat: vec4f,           // factor, roughness factor, normal scale, unused.
    sheen: vec4f,               // rgb colour factor, a: roughness factor.
    specularGlossiness: vec4f,  // rgb specular factor, a: glossiness factor.
    // KHR_materials_transmission factor, KHR_materials_volume thickness factor and attenuation
    // distance (0: none), KHR_materials_dispersion.
    transmission: vec4f,
    attenuationColor: vec4f,    // rgb: KHR_materials_volume's attenuation colour.
    // x: shading model (0 metallic-roughness, 1 specular-glossiness, 2 unlit);
    // y: kMaterial* feature bits.
    flags: vec4u,
    slots: array<TextureSlot, 12>,
}

const kModelMetallicRoughness = 0u;
const kModelSpecularGlossiness = 1u;
const kModelUnlit = 2u;
const kMaterialNormalMap = 1u;
const kMaterialClearcoatNormalMap = 2u;
const kMaterialClearcoat = 4u;
const kMaterialSheen = 8u;
const kMaterialSpecular = 16u;
const kMaterialTransmission = 1024u;
const kMaterialVolume = 2048u;

const kBaseColorSlot = 0u;
const kMetallicRoughnessSlot = 1u;
const kNormalSlot = 2u;
const kOcclusionSlot = 3u;
const kEmissiveSlot = 4u;
const kSpecularSlot = 5u;
const kSpecularColorSlot = 6u;
const kClearcoatSlot = 7u;
const kClearcoatRoughnessSlot = 8u;
const kClearcoatNormalSlot = 9u;
const kSheenColorSlot = 10u;
const kSheenRoughnessSlot = 11u;

@group(2) @binding(0) var<uniform> material: Material;
#if MATERIAL_TEXTURES
@group(2) @binding(1) var baseColorSampler: sampler;
@group(2) @binding(2) var baseColorTexture: texture_2d<f32>;
@group(2) @binding(3) var metallicRoughnessSampler: sampler;
@group(2) @binding(4) var metallicRoughnessTexture: texture_2d<f32>;
@group(2) @binding(5) var normalSampler: sampler;
@group(2) @binding(6) var normalTexture: texture_2d<f32>;
@group(2) @binding(7) var occlusionSampler: sampler;
@group(2) @binding(8) var occlusionTexture: texture_2d<f32>;
@group(2) @binding(9) var emissiveSampler: sampler;
@group(2) @binding(10) var emissiveTexture: texture_2d<f32>;
@group(2) @binding(11) var specularSampler: sampler;
@group(2) @binding(12) var specularTexture: texture_2d<f32>;
@group(2) @binding(13) var specularColorSampler: sampler;
@group(2) @binding(14) var specularColorTexture: texture_2d<f32>;
@group(2) @binding(15) var clearcoatSampler: sampler;
@group(2) @binding(16) var clearcoatTexture: texture_2d<f32>;
@group(2) @binding(17) var clearcoatRoughnessSampler: sampler;
@group(2) @binding(18) var clearcoatRoughnessTexture: texture_2d<f32>;
@group(2) @binding(19) var clearcoatNormalSampler: sampler;
@group(2) @binding(20) var clearcoatNormalTexture: texture_2d<f32>;
@group(2) @binding(21) var sheenColorSampler: sampler;
@group(2) @binding(22) var sheenColorTexture: texture_2d<f32>;
@group(2) @binding(23) var sheenRoughnessSampler: sampler;
@group(2) @binding(24) var sheenRoughnessTexture: texture_2d<f32>;
#endif

fn slotUv(slot: u32, uv0: vec2f, uv1: vec2f) -> vec2f {
    let transform = material.slots[slot];
    let uvw = vec3f(select(uv0, uv1, transform.row0.w > 0.5), 1.0);
    return vec2f(dot(transform.row0.xyz, uvw), dot(transform.row1.xyz, uvw));
}
