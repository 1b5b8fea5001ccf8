// KHR_materials_diffuse_transmission, as the Khronos Sample Renderer shades it: a share of the
// diffuse layer (diffuseTransmissionFactor times the alpha of its texture) is replaced by
// Lambertian light arriving from the far side of the surface, tinted by
// diffuseTransmissionColorFactor times its texture (RGB, sRGB). Image-based light reads the
// irradiance about the negated normal, punctual lights shine through a Lambertian BTDF from
// behind; with KHR_materials_volume both are absorbed over the volume's thickness
// (Beer-Lambert, transmission.wgsl's volumeAttenuation). The specular layer above it is
// unchanged. Needs brdf.wgsl, scene_lighting.wgsl, material.wgsl, material_samples.wgsl and
// transmission.wgsl.

// What shadeSurface knows of a diffusely transmissive material at one point.
struct DiffuseTransmission {
    factor: f32,               // How much of the diffuse layer is transmitted light (0..1).
    color: vec3f,              // Its tint.
    thickness: f32,            // World units the light crosses (0 without a volume).
    attenuationDistance: f32,  // 0: no absorption.
    attenuationColor: vec3f,
}

// The material's diffuse transmission at a point; modelScale: the lengths of the world matrix's
// axes (the volume's thickness is in the mesh's units; the reference scales it by their mean).
fn diffuseTransmissionAt(samples: MaterialSamples, modelScale: vec3f) -> DiffuseTransmission {
    var result: DiffuseTransmission;
    result.factor = clamp(material.diffuseTransmission.a * samples.diffuseTransmission, 0.0, 1.0);
    result.color = material.diffuseTransmission.rgb * samples.diffuseTransmissionColor;
    if ((material.flags.y & kMaterialVolume) != 0u) {
        let meanScale = (modelScale.x + modelScale.y + modelScale.z) / 3.0;
        result.thickness = material.transmission.y * samples.thickness * meanScale;
        result.attenuationDistance = material.transmission.z;
        result.attenuationColor = material.attenuationColor.rgb;
    }
    return result;
}

fn diffuseTransmissionAbsorbed(surface: DiffuseTransmission, radiance: vec3f) -> vec3f {
    return volumeAttenuation(radiance, surface.thickness, surface.attenuationColor,
                             surface.attenuationDistance);
}

// Image-based light through the surface: the environment's irradiance on the far side.
fn diffuseTransmissionEnvironment(surface: DiffuseTransmission, n: vec3f) -> vec3f {
    return diffuseTransmissionAbsorbed(surface, environmentIrradiance(-n) * surface.color);
}

// A punctual light's radiance through the surface (l: towards the light): Lambertian about the
// negated normal, so light from behind passes and light from the front does not.
fn diffuseTransmissionPunctual(surface: DiffuseTransmission, radiance: vec3f, n: vec3f,
                               l: vec3f) -> vec3f {
    let backLight = radiance * clamp(dot(-n, l), 0.0, 1.0) * surface.color / kPi;
    return diffuseTransmissionAbsorbed(surface, backLight);
}
