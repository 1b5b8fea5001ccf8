// Group 2: one glTF material (MaterialResources in C++). The uniform holds every factor and,
// for each of the nineteen texture slots, the texCoord set, KHR_texture_transform and sampler;
// with MATERIAL_TEXTURES each slot has its own texture (a 1-pixel default when the material has
// none: white, so that factors multiply through unchanged) and the material binds a palette of
// four samplers (its glTF samplers, render/SamplerPalette.h) that the slots share: each slot's
// uniform names its entry, and slotSampler* pick it (one sampler per slot would pass the 16 a
// shader stage may bind). Materials with no texture at all bind the uniform only and read
// white.
//
// Written by hand to match C++: the slot table (render/MaterialSlots.h: names, bindings, slot
// indices), MaterialUniform and the kMaterial*/kModel* values (render/MaterialUniform.h).
// tests/unit/render/MaterialWgslTest.cpp fails when they disagree.

// Rows of the slot's 2x3 texture transform applied to (u, v, 1); row0.w: 1 reads TEXCOORD_1;
// row1.w: the palette entry of the slot's sampler (0 to 3).
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
    iridescence: vec4f,         // factor, film IOR, thickness minimum, maximum (nanometres).
    anisotropy: vec4f,          // cos(rotation), sin(rotation), strength, unused.
    // KHR_materials_transmission factor, KHR_materials_volume thickness factor and attenuation
    // distance (0: none), KHR_materials_dispersion.
    transmission: vec4f,
    attenuationColor: vec4f,    // rgb: KHR_materials_volume's attenuation colour.
    // KHR_materials_diffuse_transmission: rgb colour factor, a: factor.
    diffuseTransmission: vec4f,
    // x: shading model (0 metallic-roughness, 1 specular-glossiness, 2 unlit);
    // y: kMaterial* feature bits; z: 1 + the material's index (segmentation); w: bit i set when
    // slot i binds a texture of its own (the others read white without sampling).
    flags: vec4u,
    slots: array<TextureSlot, 19>,
}

const kModelMetallicRoughness = 0u;
const kModelSpecularGlossiness = 1u;
const kModelUnlit = 2u;
const kMaterialNormalMap = 1u;
const kMaterialClearcoatNormalMap = 2u;
const kMaterialClearcoat = 4u;
const kMaterialSheen = 8u;
const kMaterialSpecular = 16u;
const kMaterialIridescence = 32u;
const kMaterialAnisotropy = 64u;
const kMaterialAnisotropyTexture = 128u;
const kMaterialTransmission = 1024u;
const kMaterialVolume = 2048u;
const kMaterialDiffuseTransmission = 4096u;

// The feature bits this pipeline shades: a variant without MATERIAL_EXTENSIONS (its materials
// use none of them) masks their bits off, so the compiler drops their code as dead.
#if MATERIAL_EXTENSIONS
const kCompiledFeatures = 0xffffffffu;
#else
const kCompiledFeatures = ~(kMaterialIridescence | kMaterialAnisotropy |
                            kMaterialAnisotropyTexture | kMaterialTransmission | kMaterialVolume |
                            kMaterialDiffuseTransmission);
#endif

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
const kIridescenceSlot = 12u;
const kIridescenceThicknessSlot = 13u;
const kAnisotropySlot = 14u;
const kTransmissionSlot = 15u;
const kThicknessSlot = 16u;
const kDiffuseTransmissionSlot = 17u;
const kDiffuseTransmissionColorSlot = 18u;

// `material`, which the functions here read, is the including shader's: the group 2 uniform
// of material_uniform.wgsl (mesh.wgsl), or the visibility shading's per-pixel copy.
#if MATERIAL_TEXTURES
@group(2) @binding(1) var materialSampler0: sampler;
@group(2) @binding(2) var materialSampler1: sampler;
@group(2) @binding(3) var materialSampler2: sampler;
@group(2) @binding(4) var materialSampler3: sampler;
@group(2) @binding(5) var baseColorTexture: texture_2d<f32>;
@group(2) @binding(6) var metallicRoughnessTexture: texture_2d<f32>;
@group(2) @binding(7) var normalTexture: texture_2d<f32>;
@group(2) @binding(8) var occlusionTexture: texture_2d<f32>;
@group(2) @binding(9) var emissiveTexture: texture_2d<f32>;
@group(2) @binding(10) var specularTexture: texture_2d<f32>;
@group(2) @binding(11) var specularColorTexture: texture_2d<f32>;
@group(2) @binding(12) var clearcoatTexture: texture_2d<f32>;
@group(2) @binding(13) var clearcoatRoughnessTexture: texture_2d<f32>;
@group(2) @binding(14) var clearcoatNormalTexture: texture_2d<f32>;
@group(2) @binding(15) var sheenColorTexture: texture_2d<f32>;
@group(2) @binding(16) var sheenRoughnessTexture: texture_2d<f32>;
#if MATERIAL_EXTENSIONS
@group(2) @binding(17) var iridescenceTexture: texture_2d<f32>;
@group(2) @binding(18) var iridescenceThicknessTexture: texture_2d<f32>;
@group(2) @binding(19) var anisotropyTexture: texture_2d<f32>;
@group(2) @binding(20) var transmissionTexture: texture_2d<f32>;
@group(2) @binding(21) var thicknessTexture: texture_2d<f32>;
@group(2) @binding(22) var diffuseTransmissionTexture: texture_2d<f32>;
@group(2) @binding(23) var diffuseTransmissionColorTexture: texture_2d<f32>;
#endif
#endif

fn slotUv(slot: u32, uv0: vec2f, uv1: vec2f) -> vec2f {
    let transform = material.slots[slot];
    let uvw = vec3f(select(uv0, uv1, transform.row0.w > 0.5), 1.0);
    return vec2f(dot(transform.row0.xyz, uvw), dot(transform.row1.xyz, uvw));
}

// The palette entry the slot samples with: uniform control flow follows it, so textureSample
// may be called under a switch on it.
fn slotSamplerEntry(slot: u32) -> u32 {
    return u32(material.slots[slot].row1.w);
}

#if MATERIAL_TEXTURES
#if SAMPLE_GRADIENT
// A slot's texture sampled through its palette entry, with explicit derivatives (compute
// shaders, which have none).
fn slotSampleGrad(slotTexture: texture_2d<f32>, slot: u32, uv: vec2f, dx: vec2f,
                  dy: vec2f) -> vec4f {
#if !SAMPLER_PALETTE
    return textureSampleGrad(slotTexture, materialSampler0, uv, dx, dy);
#else
    switch slotSamplerEntry(slot) {
        case 1u: { return textureSampleGrad(slotTexture, materialSampler1, uv, dx, dy); }
        case 2u: { return textureSampleGrad(slotTexture, materialSampler2, uv, dx, dy); }
        case 3u: { return textureSampleGrad(slotTexture, materialSampler3, uv, dx, dy); }
        default: { return textureSampleGrad(slotTexture, materialSampler0, uv, dx, dy); }
    }
#endif
}
#else
// A slot's texture sampled through its palette entry, with implicit derivatives (fragment).
fn slotSample(slotTexture: texture_2d<f32>, slot: u32, uv: vec2f) -> vec4f {
#if !SAMPLER_PALETTE
    return textureSample(slotTexture, materialSampler0, uv);
#else
    switch slotSamplerEntry(slot) {
        case 1u: { return textureSample(slotTexture, materialSampler1, uv); }
        case 2u: { return textureSample(slotTexture, materialSampler2, uv); }
        case 3u: { return textureSample(slotTexture, materialSampler3, uv); }
        default: { return textureSample(slotTexture, materialSampler0, uv); }
    }
#endif
}
#endif
#endif
