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
//   PASS_TARGETS      (with MATERIALS) four more colour targets: normal, albedo, material, and
//                     depth with the segmentation id of SEGMENT_BY_MESH, SEGMENT_BY_MATERIAL
//                     or else the node (pass_targets.wgsl, render/PassTargets.h).
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
#include "material_uniform.wgsl"
#include "material_samples.wgsl"
#if PASS_TARGETS
#include "pass_targets.wgsl"
#endif
#include "surface_shading.wgsl"
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

// Only what the variant has crosses to the fragment stage: every interpolant costs the few SMs
// that shade fragments on large GPUs (a constant one too; the fragment stage substitutes it).
struct VertexOutput {
    @builtin(position) position: vec4f,
    @location(0) normal: vec3f,
    @location(1) texcoord: vec2f,
#if HAS_COLOR
    @location(2) color: vec4f,
#endif
    @location(3) worldPosition: vec3f,
#if HAS_TEXCOORD1
    @location(4) texcoord1: vec2f,
#endif
#if HAS_TANGENT
    // xyz: world tangent, w: bitangent sign (handedness, flipped for mirroring transforms).
    @location(5) tangent: vec4f,
#endif
    // 1 + node index, 1 + mesh index: the segmentation ids (the normal matrix's 4th column).
    @location(6) @interpolate(flat) ids: vec2f,
#if MATERIAL_EXTENSIONS
    // Lengths of the world matrix's axes: KHR_materials_volume's thickness is in mesh units.
    @location(7) modelScale: vec3f,
#endif
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
    let ids = transform.normal[3].xy;  // Before skinning replaces the transform.
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
    output.ids = ids;
    output.normal = (transform.normal * vec4f(normal, 0.0)).xyz;
#if MATERIAL_EXTENSIONS
    output.modelScale = vec3f(length(transform.world[0].xyz), length(transform.world[1].xyz),
                              length(transform.world[2].xyz));
#endif
#if HAS_TEXCOORD
    output.texcoord = input.texcoord;
#else
    output.texcoord = vec2f(0.0);
#endif
#if HAS_TEXCOORD1
    output.texcoord1 = input.texcoord1;
#endif
#if HAS_COLOR
    output.color = input.color;
#endif
#if HAS_TANGENT
    let linear = mat3x3f(transform.world[0].xyz, transform.world[1].xyz, transform.world[2].xyz);
    // A mirroring transform turns cross(N, T) around; the handedness must follow.
    let mirror = select(1.0, -1.0, determinant(linear) < 0.0);
    output.tangent = vec4f(linear * tangent, input.tangent.w * mirror);
#endif
    return output;
}

#if MATERIALS
// The segmentation channels (DebugChannel::Segment*): the id split into R = id % 256 and
// G = id / 256, exact in half floats; other channels pass `shaded` through.
fn segmentationColor(shaded: vec4f, ids: vec2f) -> vec4f {
    var id = 0.0;
    switch (lighting.debugChannel) {
        case 9u: {
            id = ids.x;
        }
        case 10u: {
            id = ids.y;
        }
        case 11u: {
            id = f32(material.flags.z);
        }
        default: {
            return shaded;
        }
    }
    let high = floor(id / 256.0);
    return vec4f(id - high * 256.0, high, 0.0, shaded.a);
}
#endif

#if PASS_TARGETS
@fragment
fn fragmentMain(input: VertexOutput, @builtin(front_facing) frontFacing: bool) -> PassOutputs {
#else
@fragment
fn fragmentMain(input: VertexOutput, @builtin(front_facing) frontFacing: bool) -> @location(0) vec4f {
#endif
    // What the vertex stage leaves out (VertexOutput) has its constant here.
#if HAS_COLOR
    let vertexColor = input.color;
#else
    let vertexColor = vec4f(1.0);
#endif
#if MATERIALS
#if HAS_TEXCOORD1
    let uv1 = input.texcoord1;
#else
    let uv1 = input.texcoord;
#endif
#if HAS_TANGENT
    let tangent = input.tangent;
#else
    let tangent = vec4f(0.0);
#endif
#if MATERIAL_EXTENSIONS
    let modelScale = input.modelScale;
#else
    let modelScale = vec3f(1.0);  // Read only by the extensions' shading.
#endif
    // Every slot is sampled here, in uniform control flow (implicit derivatives), whether the
    // material has a texture there or binds the 1-pixel default.
    let uv0 = input.texcoord;
    let samples = sampleMaterial(uv0, uv1, UvGradients());
    let positionDx = dpdx(input.worldPosition);
    let positionDy = dpdy(input.worldPosition);
    let uvDx = dpdx(uv0);
    let uvDy = dpdy(uv0);

    let baseColor = material.baseColorFactor * vertexColor * samples.baseColor;
#if ALPHA_MASK
    if (baseColor.a < material.alpha.x) {
        discard;
    }
#endif
    let shaded = shadeSurface(input.worldPosition, input.normal, tangent, frontFacing, baseColor,
                              samples, positionDx, positionDy, uvDx, uvDy, modelScale);
#if PASS_TARGETS
#if SEGMENT_BY_MATERIAL
    let id = f32(material.flags.z);
#elif SEGMENT_BY_MESH
    let id = input.ids.y;
#else
    let id = input.ids.x;
#endif
    return passOutputs(displayColor(shaded), shaded.a, id);
#else
    return displayColor(segmentationColor(shaded, input.ids));
#endif
#else
    return displayColor(vec4f(shade(vertexColor.rgb, input.normal), 1.0));
#endif
}
