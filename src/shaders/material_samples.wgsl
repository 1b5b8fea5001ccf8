// Every texture slot of the material (material.wgsl) sampled at one surface point. A fragment
// shader samples with implicit derivatives; with SAMPLE_GRADIENT (compute shaders, which have
// none) the caller passes the screen-space derivatives of both texture coordinate sets, and each
// slot's KHR_texture_transform applies to them as to the coordinates.

struct MaterialSamples {
    baseColor: vec4f,
    metallicRoughness: vec4f,
    normal: vec3f,
    occlusion: f32,
    emissive: vec3f,
    specular: f32,
    specularColor: vec3f,
    clearcoat: f32,
    clearcoatRoughness: f32,
    clearcoatNormal: vec3f,
    sheenColor: vec3f,
    sheenRoughness: f32,
    iridescence: f32,
    iridescenceThickness: f32,
    anisotropy: vec3f,
    transmission: f32,
    thickness: f32,
    diffuseTransmission: f32,
    diffuseTransmissionColor: vec3f,
}

// d(uv)/dx and d(uv)/dy of TEXCOORD_0 and TEXCOORD_1 (unused without SAMPLE_GRADIENT).
struct UvGradients {
    dx0: vec2f,
    dy0: vec2f,
    dx1: vec2f,
    dy1: vec2f,
}

#if MATERIAL_TEXTURES
// The slot's texture transform applied to a derivative (its linear part only).
fn slotUvGradient(slot: u32, d0: vec2f, d1: vec2f) -> vec2f {
    let transform = material.slots[slot];
    let d = select(d0, d1, transform.row0.w > 0.5);
    return vec2f(dot(transform.row0.xy, d), dot(transform.row1.xy, d));
}

fn sampleSlot(slotTexture: texture_2d<f32>, slot: u32, uv0: vec2f, uv1: vec2f,
              gradients: UvGradients) -> vec4f {
    // A slot without a texture of its own binds the 1-pixel white default: skip the fetch (a
    // uniform branch), which a textured material's seventeen slots would otherwise all pay.
    if ((material.flags.w & (1u << slot)) == 0u) {
        return vec4f(1.0);
    }
#if SAMPLE_GRADIENT
    return slotSampleGrad(slotTexture, slot, slotUv(slot, uv0, uv1),
                          slotUvGradient(slot, gradients.dx0, gradients.dx1),
                          slotUvGradient(slot, gradients.dy0, gradients.dy1));
#else
    return slotSample(slotTexture, slot, slotUv(slot, uv0, uv1));
#endif
}
#endif

// The extensions' slots as the white 1-pixel default reads them.
fn whiteExtensionSamples(samples: ptr<function, MaterialSamples>) {
    (*samples).iridescence = 1.0;
    (*samples).iridescenceThickness = 1.0;
    (*samples).anisotropy = vec3f(1.0);
    (*samples).transmission = 1.0;
    (*samples).thickness = 1.0;
    (*samples).diffuseTransmission = 1.0;
    (*samples).diffuseTransmissionColor = vec3f(1.0);
}

fn sampleMaterial(uv0: vec2f, uv1: vec2f, gradients: UvGradients) -> MaterialSamples {
    var samples: MaterialSamples;
#if MATERIAL_TEXTURES
    samples.baseColor =
        sampleSlot(baseColorTexture, kBaseColorSlot, uv0, uv1, gradients);
    samples.metallicRoughness =
        sampleSlot(metallicRoughnessTexture, kMetallicRoughnessSlot, uv0, uv1, gradients);
    samples.normal =
        sampleSlot(normalTexture, kNormalSlot, uv0, uv1, gradients).rgb;
    samples.occlusion =
        sampleSlot(occlusionTexture, kOcclusionSlot, uv0, uv1, gradients).r;
    samples.emissive =
        sampleSlot(emissiveTexture, kEmissiveSlot, uv0, uv1, gradients).rgb;
    samples.specular =
        sampleSlot(specularTexture, kSpecularSlot, uv0, uv1, gradients).a;
    samples.specularColor =
        sampleSlot(specularColorTexture, kSpecularColorSlot, uv0, uv1, gradients).rgb;
    samples.clearcoat =
        sampleSlot(clearcoatTexture, kClearcoatSlot, uv0, uv1, gradients).r;
    samples.clearcoatRoughness =
        sampleSlot(clearcoatRoughnessTexture, kClearcoatRoughnessSlot, uv0, uv1, gradients).g;
    samples.clearcoatNormal =
        sampleSlot(clearcoatNormalTexture, kClearcoatNormalSlot, uv0, uv1, gradients).rgb;
    samples.sheenColor =
        sampleSlot(sheenColorTexture, kSheenColorSlot, uv0, uv1, gradients).rgb;
    samples.sheenRoughness =
        sampleSlot(sheenRoughnessTexture, kSheenRoughnessSlot, uv0, uv1, gradients).a;
#if MATERIAL_EXTENSIONS
    samples.iridescence =
        sampleSlot(iridescenceTexture, kIridescenceSlot, uv0, uv1, gradients).r;
    samples.iridescenceThickness =
        sampleSlot(iridescenceThicknessTexture, kIridescenceThicknessSlot, uv0, uv1, gradients).g;
    samples.anisotropy = sampleSlot(anisotropyTexture, kAnisotropySlot, uv0, uv1, gradients).rgb;
    samples.transmission =
        sampleSlot(transmissionTexture, kTransmissionSlot, uv0, uv1, gradients).r;
    samples.thickness = sampleSlot(thicknessTexture, kThicknessSlot, uv0, uv1, gradients).g;
    samples.diffuseTransmission = sampleSlot(diffuseTransmissionTexture, kDiffuseTransmissionSlot,
                                             uv0, uv1, gradients).a;
    samples.diffuseTransmissionColor =
        sampleSlot(diffuseTransmissionColorTexture, kDiffuseTransmissionColorSlot, uv0, uv1,
                   gradients).rgb;
#else
    // Their shading is compiled out (kCompiledFeatures): what they would read is never used.
    whiteExtensionSamples(&samples);
#endif
#else
    // No texture anywhere: every slot reads white, as the 1-pixel default would.
    samples.baseColor = vec4f(1.0);
    samples.metallicRoughness = vec4f(1.0);
    samples.normal = vec3f(1.0);
    samples.occlusion = 1.0;
    samples.emissive = vec3f(1.0);
    samples.specular = 1.0;
    samples.specularColor = vec3f(1.0);
    samples.clearcoat = 1.0;
    samples.clearcoatRoughness = 1.0;
    samples.clearcoatNormal = vec3f(1.0);
    samples.sheenColor = vec3f(1.0);
    samples.sheenRoughness = 1.0;
    whiteExtensionSamples(&samples);
#endif
    return samples;
}
