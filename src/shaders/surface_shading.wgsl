// glTF's physically based shading of one surface point, shared by mesh.wgsl's fragment shader
// and the visibility strategy's compute resolve (visibility_shade.wgsl): the tangent frame, the
// lights and the material's extensions. Needs frame.wgsl, scene_lighting.wgsl, brdf.wgsl,
// material.wgsl and material_samples.wgsl, and HAS_TANGENT as mesh.wgsl defines it.
#include "iridescence.wgsl"
#include "anisotropy.wgsl"

#include "transmission.wgsl"
#include "diffuse_transmission.wgsl"

struct SurfaceFrame {
    normal: vec3f,    // Shading normal (normal map applied).
    geometric: vec3f, // Interpolated vertex normal, facing the viewer's side.
    tangent: vec3f,
    bitangent: vec3f,
}

// The tangent frame: TANGENT when bound, otherwise derived from screen-space derivatives of
// position and texture coordinates (what the Khronos reference does for models without
// tangents). The derived bitangent takes the sign of dP/dv, so mirrored UVs stay correct.
fn surfaceFrame(vertexNormal: vec3f, vertexTangent: vec4f, frontFacing: bool, positionDx: vec3f,
                positionDy: vec3f, uvDx: vec2f, uvDy: vec2f) -> SurfaceFrame {
    var frame: SurfaceFrame;
    var normal = vertexNormal;
    if (dot(normal, normal) < 1e-12) {
        normal = cross(positionDx, positionDy);  // Flat, for geometry without usable normals.
    }
    var ng = normalize(normal);
#if HAS_TANGENT
    var t = vertexTangent.xyz - ng * dot(ng, vertexTangent.xyz);
    t = select(vec3f(1.0, 0.0, 0.0), normalize(t), dot(t, t) > 1e-12);
    var b = cross(ng, t) * select(1.0, -1.0, vertexTangent.w < 0.0);
#else
    var du = uvDx;
    var dv = uvDy;
    if (length(du) + length(dv) <= 1e-6) {
        du = vec2f(1.0, 0.0);
        dv = vec2f(0.0, 1.0);
    }
    let determinantUv = du.x * dv.y - dv.x * du.y;
    let safeDeterminant = select(determinantUv, 1e-12, abs(determinantUv) < 1e-12);
    let dPdu = (dv.y * positionDx - du.y * positionDy) / safeDeterminant;
    let dPdv = (du.x * positionDy - dv.x * positionDx) / safeDeterminant;
    var t = dPdu - ng * dot(ng, dPdu);
    if (dot(t, t) < 1e-20) {
        t = select(vec3f(0.0, 0.0, 1.0), vec3f(1.0, 0.0, 0.0), abs(ng.x) < 0.9);
        t = t - ng * dot(ng, t);
    }
    t = normalize(t);
    var b = cross(ng, t);
    // glTF's bitangent points up the image, against growing v.
    if (dot(b, dPdv) > 0.0) {
        b = -b;
    }
#endif
    if (!frontFacing) {
        t = -t;
        b = -b;
        ng = -ng;
    }
    frame.geometric = ng;
    frame.normal = ng;
    frame.tangent = t;
    frame.bitangent = b;
    return frame;
}

fn perturb(frame: SurfaceFrame, sampled: vec3f, scale: f32) -> vec3f {
    let tangentSpace = vec3f((sampled.xy * 2.0 - 1.0) * scale, sampled.z * 2.0 - 1.0);
    let n = mat3x3f(frame.tangent, frame.bitangent, frame.geometric) * tangentSpace;
    return select(frame.geometric, normalize(n), dot(n, n) > 1e-12);
}

fn maxComponent(v: vec3f) -> f32 {
    return max(v.x, max(v.y, v.z));
}

// Light arriving from a punctual light: direction towards it and radiance (KHR_lights_punctual:
// inverse-square falloff, smooth range window, spot cone).
struct IncomingLight {
    direction: vec3f,
    radiance: vec3f,
}

fn incomingLight(light: PunctualLight, position: vec3f) -> IncomingLight {
    var result: IncomingLight;
    var attenuation = 1.0;
    if (light.kind == 0u) {
        result.direction = -light.direction;
    } else {
        let toLight = light.position - position;
        let distanceSquared = max(dot(toLight, toLight), 1e-8);
        result.direction = toLight * inverseSqrt(distanceSquared);
        if (light.range > 0.0) {
            let ratio = sqrt(distanceSquared) / light.range;
            attenuation = clamp(1.0 - ratio * ratio * ratio * ratio, 0.0, 1.0) / distanceSquared;
        } else {
            attenuation = 1.0 / distanceSquared;
        }
        if (light.kind == 2u) {
            let cosine = dot(light.direction, -result.direction);
            attenuation *= smoothstep(light.outerConeCos, light.innerConeCos, cosine);
        }
    }
    result.radiance = light.color * light.intensity * attenuation;
    return result;
}

// Specular reflection of the prefiltered environment for a direction and roughness.
fn environmentSpecular(direction: vec3f, roughness: f32) -> vec3f {
    return environmentRadiance(direction, roughness * (lighting.specularLevels - 1.0));
}

// The linear colour and alpha of a surface point. baseColor: the material's factor times the
// vertex colour and the base colour sample (alpha tested already, for MASK); samples: every
// texture slot at the point; the derivatives: of the world position and TEXCOORD_0 per pixel;
// modelScale: the lengths of the world matrix's axes (a volume's thickness is in mesh units).
// The triangle's own normal from the position's screen derivatives (flat across the triangle):
// framebuffer y runs down, so cross(dy, dx) faces the viewer whatever the winding
// (DebugChannel::GeometricNormal). `fallback` where the triangle has no area on screen.
fn faceNormal(positionDx: vec3f, positionDy: vec3f, fallback: vec3f) -> vec3f {
    let face = cross(positionDy, positionDx);
    if (dot(face, face) > 1e-20) {
        return normalize(face);
    }
    return fallback;
}

fn shadeSurface(worldPosition: vec3f, vertexNormal: vec3f, vertexTangent: vec4f,
                frontFacing: bool, baseColor: vec4f, samples: MaterialSamples,
                positionDx: vec3f, positionDy: vec3f, uvDx: vec2f, uvDy: vec2f,
                modelScale: vec3f) -> vec4f {
    let baseColorSample = samples.baseColor;
    let metallicRoughnessSample = samples.metallicRoughness;
    let normalSample = samples.normal;
    let occlusionSample = samples.occlusion;
    let emissiveSample = samples.emissive;
    let specularSample = samples.specular;
    let specularColorSample = samples.specularColor;
    let clearcoatSample = samples.clearcoat;
    let clearcoatRoughnessSample = samples.clearcoatRoughness;
    let clearcoatNormalSample = samples.clearcoatNormal;
    let sheenColorSample = samples.sheenColor;
    let sheenRoughnessSample = samples.sheenRoughness;
    // BLEND alpha is opacity; OPAQUE and MASK fragments are fully opaque once drawn (glTF).
    let alpha = select(1.0, baseColor.a, material.alpha.y > 0.5);
    let model = material.flags.x;
    let features = material.flags.y & kCompiledFeatures;
    let emissive = material.emissive.rgb * emissiveSample;
    if (model == kModelUnlit) {
        // The geometric channels hold the surface's geometry whatever its shading.
        switch (lighting.debugChannel) {
            case 12u: {
                return vec4f(faceNormal(positionDx, positionDy, normalize(vertexNormal)) * 0.5 + 0.5,
                             alpha);
            }
            case 13u: {
                return vec4f(worldPosition, alpha);
            }
            default: {
            }
        }
        return vec4f(baseColor.rgb, alpha);
    }

    var surface = surfaceFrame(vertexNormal, vertexTangent, frontFacing, positionDx, positionDy,
                               uvDx, uvDy);
    if ((features & kMaterialNormalMap) != 0u) {
        surface.normal = perturb(surface, normalSample, material.metallicRoughness.z);
    }
    let n = surface.normal;
    // Orthographic projections (w row 0 0 0 1) view along the camera's -Z everywhere.
    let orthographic = frame.projection[3][3] == 1.0;
    let cameraBack = vec3f(frame.view[0][2], frame.view[1][2], frame.view[2][2]);
    let v = select(normalize(frame.cameraPosition - worldPosition), cameraBack,
                   orthographic);
    let nDotV = clamp(dot(n, v), 0.0, 1.0);

    // The surface in the metallic-roughness terms the BRDF uses.
    var metallic = clamp(material.metallicRoughness.x * metallicRoughnessSample.b, 0.0, 1.0);
    var roughness = material.metallicRoughness.y * metallicRoughnessSample.g;
    var albedo = baseColor.rgb;  // Diffuse colour of the dielectric part; F0 of the metal part.
    let ior = material.alpha.z;
    let iorF0 = select(pow((ior - 1.0) / (ior + 1.0), 2.0), 1.0, ior == 0.0);
    var f0Dielectric = vec3f(iorF0);
    var specularWeight = 1.0;
    if ((features & kMaterialSpecular) != 0u) {
        specularWeight = material.specular.a * specularSample;
        f0Dielectric = min(f0Dielectric * material.specular.rgb * specularColorSample, vec3f(1.0));
    }
    if (model == kModelSpecularGlossiness) {
        // The specular-glossiness texture occupies the metallic-roughness slot.
        let specularGlossiness = metallicRoughnessSample;
        let specularColor = material.specularGlossiness.rgb * specularGlossiness.rgb;
        roughness = 1.0 - material.specularGlossiness.a * specularGlossiness.a;
        metallic = 0.0;
        f0Dielectric = specularColor;
        specularWeight = 1.0;
        albedo = baseColor.rgb * (1.0 - maxComponent(specularColor));
    }
    roughness = clamp(roughness, 0.0, 1.0);
    let alphaRoughness = roughness * roughness;
    let occlusion = 1.0 + material.metallicRoughness.w * (occlusionSample - 1.0);

    // KHR_materials_iridescence: the thin film's reflectance over the dielectric and over the
    // metal replaces their Fresnel terms, by the film's factor (none where it has no thickness).
    var iridescence = 0.0;
    var iridescenceDielectric = vec3f(0.0);
    var iridescenceMetal = vec3f(0.0);
    if ((features & kMaterialIridescence) != 0u) {
        let film = material.iridescence;
        let thickness = mix(film.z, film.w, samples.iridescenceThickness);
        iridescence = select(clamp(film.x * samples.iridescence, 0.0, 1.0), 0.0, thickness <= 0.0);
        iridescenceDielectric = iridescenceFresnel(film.y, nDotV, thickness, f0Dielectric);
        iridescenceMetal = iridescenceFresnel(film.y, nDotV, thickness, baseColor.rgb);
    }
    // KHR_materials_anisotropy: a direction in the tangent plane stretches the specular lobe.
    let anisotropic = (features & kMaterialAnisotropy) != 0u;
    var anisotropy = Anisotropy(surface.tangent, surface.bitangent, 0.0);
    if (anisotropic) {
        anisotropy = anisotropyAt(surface, samples.anisotropy,
                                  (features & kMaterialAnisotropyTexture) != 0u);
    }
    // KHR_materials_transmission: the diffuse layer gives way to light from behind.
    let transmissive = (features & kMaterialTransmission) != 0u;
    var transmission: TransmissiveSurface;
    if (transmissive) {
        transmission.factor = clamp(material.transmission.x * samples.transmission, 0.0, 1.0);
        transmission.thickness = material.transmission.y * samples.thickness;
        transmission.ior = ior;
        transmission.dispersion = material.transmission.w;
        transmission.attenuationDistance = material.transmission.z;
        transmission.attenuationColor = material.attenuationColor.rgb;
        transmission.modelScale = modelScale;
    }

    // KHR_materials_diffuse_transmission: the diffuse layer gives way to light from the far side.
    let diffuselyTransmissive = (features & kMaterialDiffuseTransmission) != 0u;
    var diffuseTransmission: DiffuseTransmission;
    if (diffuselyTransmissive) {
        diffuseTransmission = diffuseTransmissionAt(samples, modelScale);
    }

    var color = vec3f(0.0);
    // Image-based light: split-sum specular, Lambertian irradiance; occlusion applies here only.
    let lut = brdfLutAt(nDotV, roughness);
    if (lighting.imageBasedLighting != 0u) {
        let diffuseLight = environmentIrradiance(n);
        var reflectionNormal = n;
        if (anisotropic) {
            reflectionNormal = anisotropicBentNormal(n, v, roughness, anisotropy);
        }
        let specularLight = environmentSpecular(reflect(-v, reflectionNormal), roughness);
        var diffuse = diffuseLight * albedo;
        if (diffuselyTransmissive) {
            diffuse = mix(diffuse, diffuseTransmissionEnvironment(diffuseTransmission, n),
                          diffuseTransmission.factor);
        }
        if (transmissive) {
            let refracted =
                volumeRefraction(transmission, n, v, worldPosition, roughness, baseColor.rgb);
            diffuse = mix(diffuse, refracted, transmission.factor);
        }
        let dielectricFresnel = iblFresnel(f0Dielectric, specularWeight, roughness, nDotV, lut.rg);
        let metalFresnel = iblFresnel(baseColor.rgb, 1.0, roughness, nDotV, lut.rg);
        var dielectric = mix(diffuse, specularLight, dielectricFresnel);
        var metal = metalFresnel * specularLight;
        if (iridescence > 0.0) {
            dielectric = mix(dielectric,
                             mixPerChannel(diffuse, specularLight, iridescenceDielectric),
                             iridescence);
            metal = mix(metal, specularLight * iridescenceMetal, iridescence);
        }
        color += mix(dielectric, metal, metallic) * occlusion;
    } else if (transmissive) {
        // Light from behind is not the environment's: it passes without image-based lighting
        // too (as the reference computes it whenever transmission is on), less what the
        // surface reflects.
        let refracted =
            volumeRefraction(transmission, n, v, worldPosition, roughness, baseColor.rgb);
        let dielectricFresnel = iblFresnel(f0Dielectric, specularWeight, roughness, nDotV, lut.rg);
        color += (1.0 - metallic) * (1.0 - dielectricFresnel) * refracted * transmission.factor;
    }
    // Punctual lights.
    for (var i = 0u; i < lighting.lightCount; i++) {
        let light = incomingLight(lights[i], worldPosition);
        let l = light.direction;
        let h = normalize(l + v);
        let nDotL = clamp(dot(n, l), 0.0, 1.0);
        if (nDotL <= 0.0 && !transmissive && !diffuselyTransmissive) {
            continue;  // Light from behind reaches only transmissive surfaces.
        }
        let nDotH = clamp(dot(n, h), 0.0, 1.0);
        let vDotH = clamp(dot(v, h), 0.0, 1.0);
        let incident = light.radiance * nDotL;
        var diffuse = incident * albedo / kPi;
        if (diffuselyTransmissive) {
            let through = diffuseTransmissionPunctual(diffuseTransmission, light.radiance, n, l);
            diffuse = mix(diffuse, through, diffuseTransmission.factor);
        }
        if (transmissive) {
            let through = punctualTransmission(transmission, lights[i], n, v, worldPosition,
                                               alphaRoughness, baseColor.rgb);
            diffuse = mix(diffuse, through, transmission.factor);
        }
        var lobe = specularGgx(alphaRoughness, nDotL, nDotV, nDotH);
        if (anisotropic) {
            lobe = specularGgxAnisotropic(alphaRoughness, anisotropy, n, v, l, h);
        }
        let specular = incident * lobe;
        let dielectricFresnel = fresnelSchlick(f0Dielectric * specularWeight,
                                               vec3f(specularWeight), vDotH);
        let metalFresnel = fresnelSchlick(baseColor.rgb, vec3f(1.0), vDotH);
        var dielectric = mix(diffuse, specular, dielectricFresnel);
        var metal = metalFresnel * specular;
        if (iridescence > 0.0) {
            dielectric = mix(dielectric, mixPerChannel(diffuse, specular, iridescenceDielectric),
                             iridescence);
            metal = mix(metal, specular * iridescenceMetal, iridescence);
        }
        color += mix(dielectric, metal, metallic);
    }

    // KHR_materials_sheen: a Charlie lobe on top, scaling the layers below by its albedo. The
    // image-based part samples the GGX-prefiltered environment at the sheen roughness.
    if ((features & kMaterialSheen) != 0u) {
        let sheenColor = material.sheen.rgb * sheenColorSample;
        let sheenRoughness = clamp(material.sheen.a * sheenRoughnessSample, 0.0, 1.0);
        let sheenLut = brdfLutAt(nDotV, sheenRoughness).b;
        var sheen = vec3f(0.0);
        if (lighting.imageBasedLighting != 0u) {
            sheen += environmentSpecular(reflect(-v, n), sheenRoughness) * sheenColor * sheenLut *
                     occlusion;
        }
        for (var i = 0u; i < lighting.lightCount; i++) {
            let light = incomingLight(lights[i], worldPosition);
            let nDotL = clamp(dot(n, light.direction), 0.0, 1.0);
            let nDotH = clamp(dot(n, normalize(light.direction + v)), 0.0, 1.0);
            sheen += light.radiance * nDotL * sheenColor *
                     distributionCharlie(sheenRoughness, nDotH) * visibilityNeubelt(nDotL, nDotV);
        }
        color = sheen + color * (1.0 - maxComponent(sheenColor) * sheenLut);
    }

    color += emissive;

    // KHR_materials_clearcoat: a dielectric coat (IOR 1.5) with its own roughness and normal
    // (the geometric normal unless the coat has a normal map).
    if ((features & kMaterialClearcoat) != 0u) {
        let coatFactor = clamp(material.clearcoat.x * clearcoatSample, 0.0, 1.0);
        let coatRoughness = clamp(material.clearcoat.y * clearcoatRoughnessSample, 0.0, 1.0);
        var coatNormal = surface.geometric;
        if ((features & kMaterialClearcoatNormalMap) != 0u) {
            coatNormal = perturb(surface, clearcoatNormalSample, material.clearcoat.z);
        }
        let coatNDotV = clamp(dot(coatNormal, v), 0.0, 1.0);
        let coatFresnel = fresnelSchlick(vec3f(0.04), vec3f(1.0), coatNDotV);
        var coat = vec3f(0.0);
        if (lighting.imageBasedLighting != 0u) {
            let coatLut = brdfLutAt(coatNDotV, coatRoughness).rg;
            coat += environmentSpecular(reflect(-v, coatNormal), coatRoughness) *
                    (0.04 * coatLut.x + coatLut.y) * occlusion;
        }
        let coatAlpha = coatRoughness * coatRoughness;
        for (var i = 0u; i < lighting.lightCount; i++) {
            let light = incomingLight(lights[i], worldPosition);
            let h = normalize(light.direction + v);
            let nDotL = clamp(dot(coatNormal, light.direction), 0.0, 1.0);
            coat += light.radiance * nDotL *
                    fresnelSchlick(vec3f(0.04), vec3f(1.0), clamp(dot(v, h), 0.0, 1.0)) *
                    specularGgx(coatAlpha, nDotL, coatNDotV, clamp(dot(coatNormal, h), 0.0, 1.0));
        }
        color = color * (1.0 - coatFactor * coatFresnel) + coat * coatFactor;
    }

#if PASS_TARGETS
    surfacePasses = SurfacePasses(n * 0.5 + 0.5, baseColor.rgb, vec3f(occlusion, roughness, metallic),
                                  -(frame.view * vec4f(worldPosition, 1.0)).z);
#endif
    switch (lighting.debugChannel) {
        case 1u: {
            color = baseColor.rgb;
        }
        case 2u: {
            color = n * 0.5 + 0.5;
        }
        case 3u: {
            color = vec3f(metallic);
        }
        case 4u: {
            color = vec3f(roughness);
        }
        case 5u: {
            color = vec3f(occlusion);
        }
        case 6u: {
            color = emissive;
        }
        case 7u: {
            color = vec3f(-(frame.view * vec4f(worldPosition, 1.0)).z);
        }
        case 8u: {
            color = vec3f(occlusion, roughness, metallic);
        }
        case 12u: {
            color = faceNormal(positionDx, positionDy, surface.geometric) * 0.5 + 0.5;
        }
        case 13u: {
            color = worldPosition;
        }
        default: {
        }
    }
    return vec4f(color, alpha);
}
