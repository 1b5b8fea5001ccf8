// The mesh shader of every strategy. Variants (ShaderVariantKey):
//   INSTANCE_STORAGE  transforms come from one storage buffer indexed by instance_index
//                     (instancing and later strategies); otherwise from a per-node uniform.
//   VISIBLE_LIST      (with INSTANCE_STORAGE) GPU culling: instance_index indexes this draw's
//                     list of visible instances, bound with a dynamic offset, so indirect
//                     draws keep firstInstance 0 (no IndirectFirstInstance feature needed).
//   MATERIALS         glTF materials, physically based (brdf.wgsl) and lit by the environment
//                     and KHR_lights_punctual (group 0); group 2 holds the material. Without
//                     it, strategies before `materials` draw vertex colours under one
//                     directional light (lighting.wgsl).
//   HAS_TEXCOORD      the primitive has TEXCOORD_0.
//   HAS_TEXCOORD1     a texture of the material reads TEXCOORD_1.
//   HAS_TANGENT       TANGENT is bound (the material has a normal map); otherwise normal maps
//                     use a tangent frame from screen-space derivatives.
//   HAS_COLOR         the primitive has COLOR_0.
//   ALPHA_MASK        fragments below the material's alphaCutoff are discarded.
//   MATERIAL_TEXTURES (with MATERIALS) the material binds textures; without it group 2 holds
//                     only the material uniform and every texture slot reads white.
//   SKINNED           JOINTS_0/WEIGHTS_0 are bound; an instance with a skin is drawn with its
//                     skin's joint matrices (world space) instead of its world matrix.
//   SKINNED_8         (with SKINNED) JOINTS_1/WEIGHTS_1 too: eight influences per vertex.
//   MORPHED           the primitive has morph targets: position, normal and tangent deltas read
//                     from a storage buffer by vertex_index, weighted by the instance's weights.
//   ANIMATED          SKINNED or MORPHED: the animation group (render/AnimationBuffers.h) is
//                     bound, as group 3 with MATERIALS and group 2 without (no material group).
// The colour target is either the sRGB output, written with the display transform applied
// (displayColor), or linear HDR (rgba16float) that a tone-mapping pass maps afterwards; a
// uniform selects which, so both share the variants.
// Vertex locations must match src/shaders/VertexLocations.h (a test checks).
#include "frame.wgsl"
#include "lighting.wgsl"
#include "scene_lighting.wgsl"
#if MATERIALS
#include "brdf.wgsl"
#include "material.wgsl"
#endif

struct Transform {
    world: mat4x4f,
    normal: mat4x4f,
}

#if INSTANCE_STORAGE
@group(1) @binding(0) var<storage, read> instances: array<Transform>;
#if VISIBLE_LIST
@group(1) @binding(1) var<storage, read> visibleInstances: array<u32>;
#endif
#else
@group(1) @binding(0) var<uniform> node: Transform;
#endif

#if ANIMATED
// One draw's animation data (a dynamic offset into one uniform buffer): where the primitive's
// morph deltas start, and for strategies that draw one node at a time (no instance storage) the
// instance's joint and weight offsets (0xffffffff: none).
struct AnimationDraw {
    // In vec4f, into morphDeltas: target t, vertex v, attribute a (0 position, 1 normal,
    // 2 tangent) lies at deltaOffset + (t * vertexCount + v) * 3 + a.
    deltaOffset: u32,
    vertexCount: u32,
    targetCount: u32,
    jointOffset: u32,
    weightOffset: u32,
}

#if MATERIALS
@group(3) @binding(0) var<uniform> animationDraw: AnimationDraw;
@group(3) @binding(1) var<storage, read> joints: array<Transform>;
@group(3) @binding(2) var<storage, read> morphWeights: array<f32>;
@group(3) @binding(3) var<storage, read> morphDeltas: array<vec4f>;
@group(3) @binding(4) var<storage, read> instanceAnimation: array<vec2u>;  // Per instance slot.
#else
@group(2) @binding(0) var<uniform> animationDraw: AnimationDraw;
@group(2) @binding(1) var<storage, read> joints: array<Transform>;
@group(2) @binding(2) var<storage, read> morphWeights: array<f32>;
@group(2) @binding(3) var<storage, read> morphDeltas: array<vec4f>;
@group(2) @binding(4) var<storage, read> instanceAnimation: array<vec2u>;  // Per instance slot.
#endif

const kNoAnimation = 0xffffffffu;
#endif

struct VertexInput {
    @builtin(instance_index) instance: u32,
#if MORPHED
    @builtin(vertex_index) vertex: u32,
#endif
    @location(0) position: vec3f,
    @location(1) normal: vec3f,
#if HAS_TEXCOORD
    @location(2) texcoord: vec2f,
#endif
#if HAS_COLOR
    @location(3) color: vec4f,
#endif
#if HAS_TANGENT
    @location(4) tangent: vec4f,
#endif
#if HAS_TEXCOORD1
    @location(5) texcoord1: vec2f,
#endif
#if SKINNED
    @location(6) joints0: vec4u,
    @location(7) weights0: vec4f,
#if SKINNED_8
    @location(8) joints1: vec4u,
    @location(9) weights1: vec4f,
#endif
#endif
}

struct VertexOutput {
    @builtin(position) position: vec4f,
    @location(0) normal: vec3f,
    @location(1) texcoord: vec2f,
    @location(2) color: vec4f,
    @location(3) worldPosition: vec3f,
    @location(4) texcoord1: vec2f,
    // xyz: world tangent, w: bitangent sign (handedness, flipped for mirroring transforms).
    @location(5) tangent: vec4f,
}

#if SKINNED
fn addJoint(sum: Transform, joint: u32, weight: f32) -> Transform {
    let matrices = joints[joint];
    return Transform(sum.world + matrices.world * weight, sum.normal + matrices.normal * weight);
}
#endif

@vertex
fn vertexMain(input: VertexInput) -> VertexOutput {
#if VISIBLE_LIST
    let slot = visibleInstances[input.instance];
    var transform = instances[slot];
#elif INSTANCE_STORAGE
    let slot = input.instance;
    var transform = instances[slot];
#else
    var transform = node;
#endif
    var position = input.position;
    var normal = input.normal;
#if HAS_TANGENT
    var tangent = input.tangent.xyz;
#endif
#if ANIMATED
#if INSTANCE_STORAGE
    let jointOffset = instanceAnimation[slot].x;
    let weightOffset = instanceAnimation[slot].y;
#else
    let jointOffset = animationDraw.jointOffset;
    let weightOffset = animationDraw.weightOffset;
#endif
#endif
#if MORPHED
    if (weightOffset != kNoAnimation) {
        for (var t = 0u; t < animationDraw.targetCount; t++) {
            let weight = morphWeights[weightOffset + t];
            if (weight == 0.0) {
                continue;
            }
            let base = animationDraw.deltaOffset +
                       (t * animationDraw.vertexCount + input.vertex) * 3u;
            position += weight * morphDeltas[base].xyz;
            normal += weight * morphDeltas[base + 1u].xyz;
#if HAS_TANGENT
            tangent += weight * morphDeltas[base + 2u].xyz;
#endif
        }
    }
#endif
#if SKINNED
    if (jointOffset != kNoAnimation) {
        var skin = Transform(mat4x4f(), mat4x4f());
        skin = addJoint(skin, jointOffset + input.joints0.x, input.weights0.x);
        skin = addJoint(skin, jointOffset + input.joints0.y, input.weights0.y);
        skin = addJoint(skin, jointOffset + input.joints0.z, input.weights0.z);
        skin = addJoint(skin, jointOffset + input.joints0.w, input.weights0.w);
#if SKINNED_8
        skin = addJoint(skin, jointOffset + input.joints1.x, input.weights1.x);
        skin = addJoint(skin, jointOffset + input.joints1.y, input.weights1.y);
        skin = addJoint(skin, jointOffset + input.joints1.z, input.weights1.z);
        skin = addJoint(skin, jointOffset + input.joints1.w, input.weights1.w);
#endif
        transform = skin;  // Joint matrices give world space: the node's transform is ignored.
    }
#endif
    var output: VertexOutput;
    let world = transform.world * vec4f(position, 1.0);
    output.position = frame.projection * frame.view * world;
    output.worldPosition = world.xyz;
    output.normal = (transform.normal * vec4f(normal, 0.0)).xyz;
#if HAS_TEXCOORD
    output.texcoord = input.texcoord;
#else
    output.texcoord = vec2f(0.0);
#endif
#if HAS_TEXCOORD1
    output.texcoord1 = input.texcoord1;
#else
    output.texcoord1 = output.texcoord;
#endif
#if HAS_COLOR
    output.color = input.color;
#else
    output.color = vec4f(1.0);
#endif
#if HAS_TANGENT
    let linear = mat3x3f(transform.world[0].xyz, transform.world[1].xyz, transform.world[2].xyz);
    // A mirroring transform turns cross(N, T) around; the handedness must follow.
    let mirror = select(1.0, -1.0, determinant(linear) < 0.0);
    output.tangent = vec4f(linear * tangent, input.tangent.w * mirror);
#else
    output.tangent = vec4f(0.0);
#endif
    return output;
}

#if MATERIALS
struct SurfaceFrame {
    normal: vec3f,    // Shading normal (normal map applied).
    geometric: vec3f, // Interpolated vertex normal, facing the viewer's side.
    tangent: vec3f,
    bitangent: vec3f,
}

// The tangent frame: TANGENT when bound, otherwise derived from screen-space derivatives of
// position and texture coordinates (what the Khronos reference does for models without
// tangents). The derived bitangent takes the sign of dP/dv, so mirrored UVs stay correct.
fn surfaceFrame(input: VertexOutput, frontFacing: bool, positionDx: vec3f,
                positionDy: vec3f, uvDx: vec2f, uvDy: vec2f) -> SurfaceFrame {
    var frame: SurfaceFrame;
    var normal = input.normal;
    if (dot(normal, normal) < 1e-12) {
        normal = cross(positionDx, positionDy);  // Flat, for geometry without usable normals.
    }
    var ng = normalize(normal);
#if HAS_TANGENT
    var t = input.tangent.xyz - ng * dot(ng, input.tangent.xyz);
    t = select(vec3f(1.0, 0.0, 0.0), normalize(t), dot(t, t) > 1e-12);
    var b = cross(ng, t) * select(1.0, -1.0, input.tangent.w < 0.0);
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
#endif

@fragment
fn fragmentMain(input: VertexOutput, @builtin(front_facing) frontFacing: bool) -> @location(0) vec4f {
#if MATERIALS
    // Every slot is sampled here, in uniform control flow (implicit derivatives), whether the
    // material has a texture there or binds the 1-pixel default.
    let uv0 = input.texcoord;
    let uv1 = input.texcoord1;
#if MATERIAL_TEXTURES
    let baseColorSample = textureSample(baseColorTexture, baseColorSampler,
                                        slotUv(kBaseColorSlot, uv0, uv1));
    let metallicRoughnessSample = textureSample(metallicRoughnessTexture,
        metallicRoughnessSampler, slotUv(kMetallicRoughnessSlot, uv0, uv1));
    let normalSample = textureSample(normalTexture, normalSampler,
                                     slotUv(kNormalSlot, uv0, uv1)).rgb;
    let occlusionSample = textureSample(occlusionTexture, occlusionSampler,
                                        slotUv(kOcclusionSlot, uv0, uv1)).r;
    let emissiveSample = textureSample(emissiveTexture, emissiveSampler,
                                       slotUv(kEmissiveSlot, uv0, uv1)).rgb;
    let specularSample = textureSample(specularTexture, specularSampler,
                                       slotUv(kSpecularSlot, uv0, uv1)).a;
    let specularColorSample = textureSample(specularColorTexture, specularColorSampler,
                                            slotUv(kSpecularColorSlot, uv0, uv1)).rgb;
    let clearcoatSample = textureSample(clearcoatTexture, clearcoatSampler,
                                        slotUv(kClearcoatSlot, uv0, uv1)).r;
    let clearcoatRoughnessSample = textureSample(clearcoatRoughnessTexture,
        clearcoatRoughnessSampler, slotUv(kClearcoatRoughnessSlot, uv0, uv1)).g;
    let clearcoatNormalSample = textureSample(clearcoatNormalTexture, clearcoatNormalSampler,
                                              slotUv(kClearcoatNormalSlot, uv0, uv1)).rgb;
    let sheenColorSample = textureSample(sheenColorTexture, sheenColorSampler,
                                         slotUv(kSheenColorSlot, uv0, uv1)).rgb;
    let sheenRoughnessSample = textureSample(sheenRoughnessTexture, sheenRoughnessSampler,
                                             slotUv(kSheenRoughnessSlot, uv0, uv1)).a;
#else
    // No texture anywhere: every slot reads white, as the 1-pixel default would.
    let baseColorSample = vec4f(1.0);
    let metallicRoughnessSample = vec4f(1.0);
    let normalSample = vec3f(1.0);
    let occlusionSample = 1.0;
    let emissiveSample = vec3f(1.0);
    let specularSample = 1.0;
    let specularColorSample = vec3f(1.0);
    let clearcoatSample = 1.0;
    let clearcoatRoughnessSample = 1.0;
    let clearcoatNormalSample = vec3f(1.0);
    let sheenColorSample = vec3f(1.0);
    let sheenRoughnessSample = 1.0;
#endif
    let positionDx = dpdx(input.worldPosition);
    let positionDy = dpdy(input.worldPosition);
    let uvDx = dpdx(uv0);
    let uvDy = dpdy(uv0);

    let baseColor = material.baseColorFactor * input.color * baseColorSample;
#if ALPHA_MASK
    if (baseColor.a < material.alpha.x) {
        discard;
    }
#endif
    // BLEND alpha is opacity; OPAQUE and MASK fragments are fully opaque once drawn (glTF).
    let alpha = select(1.0, baseColor.a, material.alpha.y > 0.5);
    let model = material.flags.x;
    let features = material.flags.y;
    let emissive = material.emissive.rgb * emissiveSample;
    if (model == kModelUnlit) {
        return displayColor(vec4f(baseColor.rgb, alpha));
    }

    var surface = surfaceFrame(input, frontFacing, positionDx, positionDy, uvDx, uvDy);
    if ((features & kMaterialNormalMap) != 0u) {
        surface.normal = perturb(surface, normalSample, material.metallicRoughness.z);
    }
    let n = surface.normal;
    // Orthographic projections (w row 0 0 0 1) view along the camera's -Z everywhere.
    let orthographic = frame.projection[3][3] == 1.0;
    let cameraBack = vec3f(frame.view[0][2], frame.view[1][2], frame.view[2][2]);
    let v = select(normalize(frame.cameraPosition - input.worldPosition), cameraBack,
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

    var color = vec3f(0.0);
    // Image-based light: split-sum specular, Lambertian irradiance; occlusion applies here only.
    let lut = brdfLutAt(nDotV, roughness);
    if (lighting.imageBasedLighting != 0u) {
        let diffuseLight = environmentIrradiance(n);
        let specularLight = environmentSpecular(reflect(-v, n), roughness);
        let diffuse = diffuseLight * albedo;
        let dielectricFresnel = iblFresnel(f0Dielectric, specularWeight, roughness, nDotV, lut.rg);
        let metalFresnel = iblFresnel(baseColor.rgb, 1.0, roughness, nDotV, lut.rg);
        let dielectric = mix(diffuse, specularLight, dielectricFresnel);
        let metal = metalFresnel * specularLight;
        color += mix(dielectric, metal, metallic) * occlusion;
    }
    // Punctual lights.
    for (var i = 0u; i < lighting.lightCount; i++) {
        let light = incomingLight(lights[i], input.worldPosition);
        let l = light.direction;
        let h = normalize(l + v);
        let nDotL = clamp(dot(n, l), 0.0, 1.0);
        if (nDotL <= 0.0) {
            continue;
        }
        let nDotH = clamp(dot(n, h), 0.0, 1.0);
        let vDotH = clamp(dot(v, h), 0.0, 1.0);
        let incident = light.radiance * nDotL;
        let diffuse = incident * albedo / kPi;
        let specular = incident * specularGgx(alphaRoughness, nDotL, nDotV, nDotH);
        let dielectricFresnel = fresnelSchlick(f0Dielectric * specularWeight,
                                               vec3f(specularWeight), vDotH);
        let metalFresnel = fresnelSchlick(baseColor.rgb, vec3f(1.0), vDotH);
        color += mix(mix(diffuse, specular, dielectricFresnel), metalFresnel * specular, metallic);
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
            let light = incomingLight(lights[i], input.worldPosition);
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
            let light = incomingLight(lights[i], input.worldPosition);
            let h = normalize(light.direction + v);
            let nDotL = clamp(dot(coatNormal, light.direction), 0.0, 1.0);
            coat += light.radiance * nDotL *
                    fresnelSchlick(vec3f(0.04), vec3f(1.0), clamp(dot(v, h), 0.0, 1.0)) *
                    specularGgx(coatAlpha, nDotL, coatNDotV, clamp(dot(coatNormal, h), 0.0, 1.0));
        }
        color = color * (1.0 - coatFactor * coatFresnel) + coat * coatFactor;
    }

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
            color = vec3f(-(frame.view * vec4f(input.worldPosition, 1.0)).z);
        }
        default: {
        }
    }
    return displayColor(vec4f(color, alpha));
#else
    return displayColor(vec4f(shade(input.color.rgb, input.normal), 1.0));
#endif
}
