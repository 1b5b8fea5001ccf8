// The mesh shader of every strategy. Variants (ShaderVariantKey):
//   INSTANCE_STORAGE  transforms come from one storage buffer indexed by instance_index
//                     (instancing and later strategies); otherwise from a per-node uniform.
//   VISIBLE_LIST      (with INSTANCE_STORAGE) GPU culling: instance_index indexes this draw's
//                     list of visible instances, bound with a dynamic offset, so indirect
//                     draws keep firstInstance 0 (no IndirectFirstInstance feature needed).
//   MATERIALS         group 2 holds the glTF material (base colour factor and texture).
//   HAS_TEXCOORD      the primitive has TEXCOORD_0.
//   HAS_COLOR         the primitive has COLOR_0.
//   ALPHA_MASK        fragments below the material's alphaCutoff are discarded.
// Vertex locations must match include/encore/shaders/VertexLocations.h (a test checks).
#include "frame.wgsl"
#include "lighting.wgsl"

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

#if MATERIALS
struct Material {
    baseColorFactor: vec4f,
    // KHR_texture_transform as the two rows of a 2x3 matrix applied to (u, v, 1).
    texcoordRow0: vec4f,
    texcoordRow1: vec4f,
    alphaCutoff: f32,
    // 1 for BLEND materials; OPAQUE and MASK ones are fully opaque once drawn (glTF).
    alphaBlend: f32,
}
@group(2) @binding(0) var<uniform> material: Material;
@group(2) @binding(1) var baseColorSampler: sampler;
@group(2) @binding(2) var baseColorTexture: texture_2d<f32>;
#endif

struct VertexInput {
    @builtin(instance_index) instance: u32,
    @location(0) position: vec3f,
    @location(1) normal: vec3f,
#if HAS_TEXCOORD
    @location(2) texcoord: vec2f,
#endif
#if HAS_COLOR
    @location(3) color: vec4f,
#endif
}

struct VertexOutput {
    @builtin(position) position: vec4f,
    @location(0) normal: vec3f,
    @location(1) texcoord: vec2f,
    @location(2) color: vec4f,
}

@vertex
fn vertexMain(input: VertexInput) -> VertexOutput {
#if VISIBLE_LIST
    let transform = instances[visibleInstances[input.instance]];
#elif INSTANCE_STORAGE
    let transform = instances[input.instance];
#else
    let transform = node;
#endif
    var output: VertexOutput;
    output.position = frame.projection * frame.view * transform.world * vec4f(input.position, 1.0);
    output.normal = (transform.normal * vec4f(input.normal, 0.0)).xyz;
#if HAS_TEXCOORD
    output.texcoord = input.texcoord;
#else
    output.texcoord = vec2f(0.0);
#endif
#if HAS_COLOR
    output.color = input.color;
#else
    output.color = vec4f(1.0);
#endif
    return output;
}

@fragment
fn fragmentMain(input: VertexOutput) -> @location(0) vec4f {
#if MATERIALS
    let uvw = vec3f(input.texcoord, 1.0);
    let uv = vec2f(dot(material.texcoordRow0.xyz, uvw), dot(material.texcoordRow1.xyz, uvw));
    let baseColor = material.baseColorFactor * input.color *
                    textureSample(baseColorTexture, baseColorSampler, uv);
#if ALPHA_MASK
    if (baseColor.a < material.alphaCutoff) {
        discard;
    }
#endif
    let alpha = select(1.0, baseColor.a, material.alphaBlend > 0.5);
#else
    let baseColor = input.color;
    let alpha = 1.0;
#endif
    return vec4f(shade(baseColor.rgb, input.normal), alpha);
}
