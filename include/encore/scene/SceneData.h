#pragma once

// SceneData is the CPU-side result of loading a glTF 2.0 asset: geometry, materials, images
// and the flattened list of mesh instances with their world matrices. It contains no WebGPU
// types; src/render maps it to GPU objects.
//
// The loader hands out data that a WebGPU renderer can use without further checks:
//  - every accessor referenced by a primitive lies inside its bufferView and buffer, has a
//    non-zero effective byteStride and, for vertex attributes, a component type/count/normalized
//    combination that exists as a WebGPU vertex format (8/16-bit 1- and 3-component attributes
//    are repacked to 4 components; non-normalized integer POSITION/NORMAL/TANGENT/TEXCOORD/COLOR
//    attributes are converted to float32);
//  - index accessors are Uint16 or Uint32 (8-bit indices are widened), tightly packed, and every
//    index value is smaller than the primitive's vertex count;
//  - sparse accessors, accessors without a bufferView, Draco- and meshopt-compressed data are
//    materialised into buffers appended after the asset's own;
//  - line loops become line strips and triangle fans become triangle lists;
//  - every primitive has POSITION and NORMAL: flat normals are generated for triangles when
//    NORMAL is absent (the primitive is de-indexed for that), and zero normals (drawn unlit) for
//    points and lines;
//  - every primitive has a material: the glTF default material is appended when needed;
//  - skins, morph targets and animations are checked (docs/animation.md): joint indices of a
//    skinned primitive are below its skin's joint count, morph targets have the primitive's
//    vertex count, animation samplers are decoded to floats with increasing key times;
//  - with LoadOptions::optimizeMeshes, indexed triangle lists are reordered for the vertex cache
//    and vertex fetch, grouped into clusters (Primitive::clusters), and with buildLevelsOfDetail
//    they get Primitive::levels (MeshOptimizer.h);
//    buffers that no primitive reads after that are emptied, so only accessors that primitives
//    reference are guaranteed to lie inside their buffer.

#include <atomic>
#include <cmath>
#include <compare>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "encore/core/Result.h"
#include "encore/core/ReusedBlocks.h"

// Strong index types for cross-references inside SceneData. An id is an index into the
// matching vector of SceneData; distinct types keep a MeshId from being used as a MaterialId.

namespace encore::scene {

template <typename Tag>
struct Id {
    static constexpr std::uint32_t kInvalid = std::numeric_limits<std::uint32_t>::max();

    std::uint32_t value = kInvalid;

    constexpr Id() = default;
    constexpr explicit Id(std::uint32_t index) : value(index) {}
    constexpr explicit Id(std::size_t index) : value(static_cast<std::uint32_t>(index)) {}

    constexpr bool valid() const { return value != kInvalid; }
    constexpr std::size_t index() const { return value; }
    constexpr auto operator<=>(const Id&) const = default;
};

using BufferId = Id<struct BufferTag>;
using BufferViewId = Id<struct BufferViewTag>;
using AccessorId = Id<struct AccessorTag>;
using MeshId = Id<struct MeshTag>;
using MaterialId = Id<struct MaterialTag>;
using TextureId = Id<struct TextureTag>;
using SamplerId = Id<struct SamplerTag>;
using ImageId = Id<struct ImageTag>;
using NodeId = Id<struct NodeTag>;
using LightId = Id<struct LightTag>;
using CameraId = Id<struct CameraTag>;
using SkinId = Id<struct SkinTag>;
using AnimationId = Id<struct AnimationTag>;
using VariantId =
    Id<struct VariantTag>;  // KHR_materials_variants: an index into SceneData::variants.

}  // namespace encore::scene

template <typename Tag>
struct std::hash<encore::scene::Id<Tag>> {
    std::size_t operator()(const encore::scene::Id<Tag>& id) const noexcept {
        return std::hash<std::uint32_t>{}(id.value);
    }
};

namespace encore::scene {

// An axis-aligned box; empty until a point is added. Points with a NaN or infinite coordinate
// are ignored, so a box is either empty or finite.
struct Bounds {
    glm::vec3 min{std::numeric_limits<float>::infinity()};
    glm::vec3 max{-std::numeric_limits<float>::infinity()};

    bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
    void extend(const glm::vec3& point) {
        if (!std::isfinite(point.x) || !std::isfinite(point.y) || !std::isfinite(point.z)) {
            return;
        }
        min = glm::min(min, point);
        max = glm::max(max, point);
    }
    void extend(const Bounds& other) {
        if (!other.empty()) {
            extend(other.min);
            extend(other.max);
        }
    }
    glm::vec3 center() const { return (min + max) * 0.5f; }
    // Radius of the sphere around center() that encloses the box.
    float radius() const { return empty() ? 0.0f : glm::length(max - min) * 0.5f; }

    // The box enclosing this box's eight corners after an affine transform.
    Bounds transformed(const glm::mat4& transform) const {
        Bounds result;
        if (empty()) {
            return result;
        }
        for (int corner = 0; corner < 8; ++corner) {
            const glm::vec3 point((corner & 1) ? max.x : min.x, (corner & 2) ? max.y : min.y,
                                  (corner & 4) ? max.z : min.z);
            result.extend(glm::vec3(transform * glm::vec4(point, 1.0f)));
        }
        return result;
    }
};

// glTF animations as the loader hands them out, and the interpolation of one sampler.
//
// The loader decodes every sampler once: key times become floats (checked finite and strictly
// increasing) and output values floats, normalised integers mapped as glTF says
// (max(c / 127, -1) for signed bytes, c / 65535 for unsigned shorts...). Channels name the node
// and the property they drive; a sampler's element width (`components`) always matches the path
// of every channel that uses it: 3 for translation and scale, 4 for rotation (x, y, z, w) and the
// number of morph targets of the node's mesh for weights. AnimationPlayer.h plays them.

enum class AnimationPath : std::uint8_t { Translation, Rotation, Scale, Weights };

enum class Interpolation : std::uint8_t {
    Step,         // The value of the key at or before t.
    Linear,       // Linear; rotations use shortest-path spherical interpolation.
    CubicSpline,  // Cubic Hermite with the file's tangents (scaled by the key interval).
};

std::string_view animationPathName(AnimationPath path);  // "translation"...
std::string_view interpolationName(Interpolation mode);  // "STEP", "LINEAR", "CUBICSPLINE"

struct AnimationSampler {
    Interpolation interpolation = Interpolation::Linear;
    std::vector<float> times;  // Seconds; at least one, finite, strictly increasing.
    // Per key: `components` floats (STEP, LINEAR), or in-tangent, value, out-tangent, each
    // `components` floats (CUBICSPLINE), as glTF stores them.
    std::vector<float> values;
    std::uint32_t components = 0;
};

struct AnimationChannel {
    std::uint32_t sampler = 0;  // Index into Animation::samplers.
    NodeId node;                // Always valid.
    AnimationPath path = AnimationPath::Translation;
};

struct Animation {
    std::string name;
    std::vector<AnimationSampler> samplers;
    // Channels whose target the loader cannot drive (no node, an unknown path, weights of a node
    // without morph targets) are left out, with a warning where glTF calls them invalid.
    std::vector<AnimationChannel> channels;
    // Seconds added to the playback time before this animation is sampled (and wrapped, when
    // looping): glTF has no such property, so Encore reads it from the animation's
    // `extras.encoreTimeOffset`. Many copies of one animated model can then share its keyframes
    // (same accessors) and still play out of step; viewers that ignore it play them in step.
    float timeOffset = 0.0f;
    float start = 0.0f;  // First key time over the channels' samplers (0 without channels).
    float end = 0.0f;    // Last key time: the animation's duration as players report it.
};

// Where a sampler was last evaluated; lets sequential evaluation skip the binary search.
// One cursor per (player, sampler); any value is valid (it is only a hint).
struct SamplerCursor {
    std::uint32_t key = 0;
};

// Evaluates `sampler` at `time` seconds into `out` (sampler.components floats; `out` must hold
// that many). Times before the first key give the first value, after the last key the last
// value. With `quaternion` (rotation channels, components == 4) LINEAR is a shortest-path slerp
// and the result of every mode is normalised (a zero quaternion becomes the identity). Never
// allocates.
void sampleAnimation(const AnimationSampler& sampler,
                     float time,
                     bool quaternion,
                     SamplerCursor& cursor,
                     std::span<float> out);

enum class ComponentType : std::uint8_t { Int8, Uint8, Int16, Uint16, Uint32, Float32 };

// Bytes of one component (1, 2 or 4).
std::uint32_t componentSize(ComponentType type);

struct Buffer {
    std::string name;  // The glTF uri, "GLB BIN chunk", or what synthesised it.
    std::vector<std::uint8_t> bytes;
};

struct BufferView {
    BufferId buffer;
    std::uint64_t byteOffset = 0;
    std::uint64_t byteLength = 0;
    std::uint32_t byteStride = 0;  // 0: tightly packed (glTF's absent byteStride).
};

struct Accessor {
    BufferViewId view;             // Always valid after loading.
    std::uint64_t byteOffset = 0;  // Relative to the view.
    std::uint32_t count = 0;
    ComponentType componentType = ComponentType::Float32;
    std::uint8_t componentCount = 1;  // 1..4; matrix accessors never reach a primitive.
    bool normalized = false;
    std::uint32_t byteStride = 0;  // Effective stride: the view's, or the element size.
    std::vector<float> min;        // As declared in the file (may be empty).
    std::vector<float> max;

    std::uint32_t elementSize() const { return componentSize(componentType) * componentCount; }
};

// Attribute semantics Encore knows. Others (custom "_NAME", TEXCOORD_2...) are skipped.
enum class Semantic : std::uint8_t {
    Position,
    Normal,
    Tangent,
    Texcoord0,
    Texcoord1,
    Color0,
    Joints0,   // Uint8 or Uint16 VEC4 (never normalised).
    Weights0,  // Float32, or normalised Uint8/Uint16, VEC4.
    Joints1,
    Weights1,
};
std::string_view semanticName(Semantic semantic);

struct VertexAttribute {
    Semantic semantic;
    AccessorId accessor;
};

// WebGPU's topologies; glTF line loops and triangle fans are converted at load.
enum class Topology : std::uint8_t { PointList, LineList, LineStrip, TriangleList, TriangleStrip };

// One morph target of a primitive: per-vertex deltas, each a Float32 VEC3 accessor (possibly
// strided: read it with readFloats or packedAccessorBytes) whose count is the primitive's
// vertexCount. A TANGENT delta has no w.
struct MorphTarget {
    std::optional<AccessorId> position;
    std::optional<AccessorId> normal;
    std::optional<AccessorId> tangent;
};

// A coarser version of a primitive's triangles, made at load by simplification
// (MeshOptimizer.h): other indices into the primitive's own vertices.
// A cluster (meshlet) of a level of detail: a run of consecutive triangles that lie close
// together (MeshOptimizer.h), with bounds for culling it as a whole. Object space.
struct Cluster {
    // Triangles counted from level 0's first index (a coarser level's clusters lie in its range).
    std::uint32_t firstTriangle = 0;
    std::uint32_t triangleCount = 0;  // 1 to kMaxTriangles.
    glm::vec3 center{0.0f};           // A sphere around every vertex of its triangles.
    float radius = 0.0f;
    // The cone of its triangles' normals (meshoptimizer's meshopt_Bounds): every triangle faces
    // away from a camera at `eye` when dot(normalize(coneApex - eye), coneAxis) >= coneCutoff.
    // A cutoff of 1 or more never culls.
    glm::vec3 coneApex{0.0f};
    glm::vec3 coneAxis{0.0f};
    float coneCutoff = 1.0f;

    static constexpr std::uint32_t kMaxTriangles = 256;
};

struct LevelOfDetail {
    AccessorId indices;  // Same bufferView and componentType as the primitive's indices.
    // How far (object-space distance, in the units of POSITION) the level's surface may lie from
    // the full-detail surface: meshoptimizer's relative error times the positions' extent
    // (meshopt_simplifyScale). A renderer picks the coarsest level whose error, projected to the
    // screen, stays under its pixel threshold.
    float error = 0.0f;
    // The level's clusters in index order, covering its triangles; empty when it has none.
    std::vector<Cluster> clusters;
};

// KHR_materials_variants: the material a primitive draws while `variant` is selected.
struct VariantMapping {
    VariantId variant;
    MaterialId material;
};

struct Primitive {
    Topology topology = Topology::TriangleList;
    std::vector<VertexAttribute> attributes;  // Sorted by semantic; Position and Normal present.
    std::optional<AccessorId> indices;        // Uint16 or Uint32.
    MaterialId material;  // Always valid: the material drawn when no variant is selected.
    // KHR_materials_variants: the variants that map this primitive to another material, sorted
    // by variant, each once (the loader refuses a variant mapped twice). Variants not listed
    // draw `material`.
    std::vector<VariantMapping> variantMaterials;
    std::uint32_t vertexCount = 0;
    Bounds bounds;  // Object-space box of the positions (without skinning or morphing).
    // Morph targets; every primitive of a mesh has the same number (Mesh::weights.size()).
    std::vector<MorphTarget> targets;
    // Levels of detail 1, 2, ... (levels[0] is level 1; `indices` is level 0), finer to
    // coarser; empty when the primitive has none (not an indexed triangle list, simplification
    // declined, or LoadOptions::buildLevelsOfDetail off). Each has at most half the triangles of
    // the one before and an error no smaller. All of a primitive's index data lies in ONE
    // bufferView: `indices` at its start (byteOffset 0), then each level at a byteOffset that is
    // a multiple of 4, all with the same componentType. A renderer binds the index buffer once,
    // at `indices` (as for level 0), and draws levels[i] with indexCount = its count and
    // firstIndex = (its byteOffset - indices' byteOffset) / index size; the binding must reach
    // the end of the view (render::GeometryBuffers' bindings do).
    std::vector<LevelOfDetail> levels;
    // Level 0's clusters (MeshOptimizer.h): in index order, each a run of consecutive triangles,
    // together covering every triangle once. Empty when the loader built none (not processed,
    // blending material, LoadOptions::optimizeMeshes off).
    std::vector<Cluster> clusters;

    std::optional<AccessorId> attribute(Semantic semantic) const;
    // The material drawn while `variant` is selected (nullopt: none, the default materials).
    MaterialId materialFor(std::optional<VariantId> variant) const;
};

struct Mesh {
    std::string name;
    std::vector<Primitive> primitives;
    // Default morph weights, one per morph target (zeros when the file gives none).
    std::vector<float> weights;
};

// KHR_texture_transform, applied to the texture coordinates before sampling.
struct TextureTransform {
    glm::vec2 offset{0.0f};
    float rotation = 0.0f;
    glm::vec2 scale{1.0f};
};

struct TextureRef {
    TextureId texture;
    std::uint32_t texCoord = 0;
    std::optional<TextureTransform> transform;
};

enum class AlphaMode : std::uint8_t { Opaque, Mask, Blend };

// KHR_materials_specular: the strength (texture: alpha channel) and colour (texture: RGB,
// sRGB) of the dielectric specular reflection.
struct SpecularExtension {
    float specularFactor = 1.0f;
    std::optional<TextureRef> specularTexture;
    glm::vec3 specularColorFactor{1.0f};
    std::optional<TextureRef> specularColorTexture;
};

// KHR_materials_clearcoat: a second, dielectric specular layer (IOR 1.5) on top.
struct ClearcoatExtension {
    float clearcoatFactor = 0.0f;
    std::optional<TextureRef> clearcoatTexture;  // Red channel.
    float clearcoatRoughnessFactor = 0.0f;
    std::optional<TextureRef> clearcoatRoughnessTexture;  // Green channel.
    std::optional<TextureRef> clearcoatNormalTexture;
    float clearcoatNormalScale = 1.0f;
};

// KHR_materials_sheen: a Charlie-distribution sheen lobe (cloth, velvet).
struct SheenExtension {
    glm::vec3 sheenColorFactor{0.0f};
    std::optional<TextureRef> sheenColorTexture;  // RGB, sRGB.
    float sheenRoughnessFactor = 0.0f;
    std::optional<TextureRef> sheenRoughnessTexture;  // Alpha channel.
};

// KHR_materials_iridescence: a thin film on the surface (soap bubbles, oil, anodised metal) whose
// interference tints the specular reflection with the viewing angle. The film is
// iridescenceThicknessMaximum nanometres thick, or with a thickness texture (green channel)
// mix(minimum, maximum, texel).
struct IridescenceExtension {
    float iridescenceFactor = 0.0f;
    std::optional<TextureRef> iridescenceTexture;  // Red channel.
    float iridescenceIor = 1.3f;
    float iridescenceThicknessMinimum = 100.0f;  // Nanometres.
    float iridescenceThicknessMaximum = 400.0f;
    std::optional<TextureRef> iridescenceThicknessTexture;  // Green channel.
};

// KHR_materials_anisotropy: the specular lobe stretched along a direction of the tangent plane
// (brushed metal). The direction is the tangent turned by anisotropyRotation (radians,
// counter-clockwise), or the texture's red-green direction turned by it; the texture's blue
// channel scales the strength.
struct AnisotropyExtension {
    float anisotropyStrength = 0.0f;
    float anisotropyRotation = 0.0f;
    std::optional<TextureRef> anisotropyTexture;  // RG direction (linear, -1..1), B strength.
};

// KHR_materials_pbrSpecularGlossiness (archived, still common). When present the material is
// shaded in the specular-glossiness model: baseColorFactor/baseColorTexture of Material hold
// the diffuse factor and texture, and metallic-roughness values are ignored.
struct SpecularGlossinessExtension {
    glm::vec3 specularFactor{1.0f};
    float glossinessFactor = 1.0f;
    std::optional<TextureRef> specularGlossinessTexture;  // RGB specular (sRGB), A glossiness.
};

// KHR_materials_transmission: light passing through a thin (or, with volume, thick) dielectric
// surface, refracted and blurred by roughness; what lies behind comes from the transmission
// pass's copy of the opaque scene.
struct TransmissionExtension {
    float transmissionFactor = 0.0f;
    std::optional<TextureRef> transmissionTexture;  // Red channel.
};

// KHR_materials_volume: the surface bounds a volume of this thickness (in the mesh's own units,
// scaled by the node's transform), absorbing along the refracted ray (Beer-Lambert): white
// light turns attenuationColor after attenuationDistance.
struct VolumeExtension {
    float thicknessFactor = 0.0f;
    std::optional<TextureRef> thicknessTexture;  // Green channel.
    float attenuationDistance = std::numeric_limits<float>::infinity();
    glm::vec3 attenuationColor{1.0f};
};

// KHR_materials_dispersion: the index of refraction spread per colour channel
// (20 / Abbe number; 0: none).
struct DispersionExtension {
    float dispersion = 0.0f;
};

// KHR_materials_diffuse_transmission: a share of the light that is not reflected specularly
// passes through the surface diffusely (a Lambertian lobe on the far side), tinted by the
// colour; thin leaves, paper, lamp shades. With KHR_materials_volume, it is absorbed over the
// thickness.
struct DiffuseTransmissionExtension {
    float diffuseTransmissionFactor = 0.0f;
    std::optional<TextureRef> diffuseTransmissionTexture;  // Alpha channel.
    glm::vec3 diffuseTransmissionColorFactor{1.0f};
    std::optional<TextureRef> diffuseTransmissionColorTexture;  // RGB, sRGB.
};

struct Material {
    std::string name;
    glm::vec4 baseColorFactor{1.0f};
    std::optional<TextureRef> baseColorTexture;
    float metallicFactor = 1.0f;
    float roughnessFactor = 1.0f;
    std::optional<TextureRef> metallicRoughnessTexture;  // Blue: metal, green: roughness.
    std::optional<TextureRef> normalTexture;
    float normalScale = 1.0f;
    std::optional<TextureRef> occlusionTexture;  // Red channel.
    float occlusionStrength = 1.0f;
    std::optional<TextureRef> emissiveTexture;
    glm::vec3 emissiveFactor{0.0f};
    float emissiveStrength = 1.0f;  // KHR_materials_emissive_strength.
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;  // Kept as written: a cutoff of 0 stays 0.
    bool doubleSided = false;
    bool isDefault = false;  // The glTF default material, appended by the loader.

    bool unlit = false;  // KHR_materials_unlit: the base colour is the output colour.
    float ior = 1.5f;    // KHR_materials_ior (0 means infinite, as the extension says).
    std::optional<SpecularExtension> specular;
    std::optional<ClearcoatExtension> clearcoat;
    std::optional<SheenExtension> sheen;
    std::optional<SpecularGlossinessExtension> specularGlossiness;
    std::optional<IridescenceExtension> iridescence;
    std::optional<AnisotropyExtension> anisotropy;
    std::optional<TransmissionExtension> transmission;
    // Only with transmission or diffuse transmission (the extension says so).
    std::optional<VolumeExtension> volume;
    std::optional<DispersionExtension> dispersion;
    std::optional<DiffuseTransmissionExtension> diffuseTransmission;
    // Material extensions present in the file that Encore does not shade (vendor extensions,
    // KHR_materials_volume_scatter, ...): the base material is drawn instead.
    std::vector<std::string> ignoredExtensions;
};

enum class Filter : std::uint8_t { Nearest, Linear };
enum class Wrap : std::uint8_t { Repeat, ClampToEdge, MirroredRepeat };

struct Sampler {
    Filter magFilter = Filter::Linear;
    Filter minFilter = Filter::Linear;
    Filter mipmapFilter = Filter::Linear;
    bool useMipmaps = true;  // False for glTF minFilter NEAREST or LINEAR.
    Wrap wrapS = Wrap::Repeat;
    Wrap wrapT = Wrap::Repeat;
};

struct Texture {
    // The image drawn: EXT_texture_webp's image when the texture has one and it decodes (or,
    // without decoding, exists), else the core `source`. Invalid when the texture names no
    // usable image.
    ImageId image;
    SamplerId sampler;  // Always valid: a default sampler is appended when needed.
    // KHR_texture_basisu's KTX2 image, which Encore cannot decode (no transcoder is packaged):
    // the texture draws `image`, its fallback source, instead (a default texture without one).
    std::optional<ImageId> basisuImage;
};

struct Image {
    std::string name;  // uri, or "image N" for embedded ones.
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    ReusedBytes rgba8;  // Empty when the image is missing or undecodable (the loader warned) or
                        // decoding was not requested.
    // The size the file declares: larger than width x height when the loader downscaled the
    // image to LoadOptions::maxImageDimension; 0 when it was not decoded from a file.
    std::uint32_t sourceWidth = 0;
    std::uint32_t sourceHeight = 0;

    bool downscaled() const { return sourceWidth > width || sourceHeight > height; }
};

struct Node {
    std::string name;
    NodeId parent;
    std::vector<NodeId> children;
    std::optional<MeshId> mesh;
    glm::mat4 local{1.0f};  // From matrix or TRS.
    glm::mat4 world{1.0f};
    // The rest pose as TRS, which animation channels override (local == T * R * S unless
    // hasMatrix). A node given by a matrix keeps the matrix as `local` and its decomposition
    // here, used only if an (invalid) animation targets it.
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // Normalised.
    glm::vec3 scale{1.0f};
    bool hasMatrix = false;
    std::optional<SkinId> skin;  // Only on nodes with a mesh.
    // Morph weights of the node's mesh: the node's `weights`, else the mesh's (empty without
    // morph targets).
    std::vector<float> weights;
};

// T * R * S as a matrix (the rotation normalised), exactly as the loader builds Node::local.
glm::mat4 composeTrs(const glm::vec3& translation,
                     const glm::quat& rotation,
                     const glm::vec3& scale);

// glTF skin: joint nodes and their inverse bind matrices (identity when the file has none).
struct Skin {
    std::string name;
    std::vector<NodeId> joints;                  // At least one.
    std::vector<glm::mat4> inverseBindMatrices;  // One per joint.
    std::optional<NodeId> skeleton;              // Informative only.
};

// One drawable occurrence of a mesh: a node of the chosen scene that references a mesh, or one
// of the EXT_mesh_gpu_instancing instances of such a node. Ordered depth-first by node.
struct Instance {
    MeshId mesh;
    NodeId node;
    glm::mat4 world{1.0f};
    glm::mat4 normalMatrix{1.0f};  // Inverse transpose of world's upper 3x3, in a mat4.
    // EXT_mesh_gpu_instancing: world == node world * instanceTransform (identity otherwise).
    glm::mat4 instanceTransform{1.0f};
};

// The inverse transpose of `world`'s upper 3x3, in a mat4. A singular matrix (a zero scale) gets
// its cofactor matrix, which is the inverse transpose up to scale; one of rank one or less, or
// one that is not finite, gets the identity: the result is always finite.
glm::mat4 normalMatrixOf(const glm::mat4& world);

// KHR_lights_punctual. Intensity is in candela (point, spot) or lux (directional).
enum class LightType : std::uint8_t { Directional, Point, Spot };

struct Light {
    std::string name;
    LightType type = LightType::Point;
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    float range = 0.0f;  // 0: unlimited (the extension's absent range).
    float innerConeAngle = 0.0f;
    float outerConeAngle = 0.7853981634f;  // pi / 4.
};

// A light placed by a node of the chosen scene, in world space. The light shines along the
// node's -Z axis.
struct LightInstance {
    LightId light;
    NodeId node;
    glm::vec3 position{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  // Normalised.
};

enum class CameraProjection : std::uint8_t { Perspective, Orthographic };

// A glTF camera as declared.
struct CameraData {
    std::string name;
    CameraProjection projection = CameraProjection::Perspective;
    float yfov = 0.8f;         // Perspective: vertical field of view, radians.
    float aspectRatio = 0.0f;  // Perspective: 0 when absent (use the target's).
    float xmag = 1.0f;         // Orthographic: half width and half height of the view.
    float ymag = 1.0f;
    float znear = 0.01f;
    float zfar = 0.0f;  // 0: infinite (perspective without zfar).
};

// A camera placed by a node of the chosen scene; `world` is the node's world matrix (the
// camera looks along its -Z axis with +Y up, scale removed).
struct CameraInstance {
    CameraId camera;
    NodeId node;
    glm::mat4 world{1.0f};
};

struct SceneData {
    std::filesystem::path sourcePath;  // The file, or the display name of an in-memory asset.
    std::vector<Buffer> buffers;
    std::vector<BufferView> bufferViews;
    std::vector<Accessor> accessors;
    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<Sampler> samplers;
    std::vector<Image> images;
    std::vector<Node> nodes;
    std::vector<Instance> instances;
    std::vector<Light> lights;
    std::vector<LightInstance> lightInstances;  // Depth-first by node, like instances.
    std::vector<CameraData> cameras;
    std::vector<CameraInstance> cameraInstances;  // Depth-first by node.
    std::vector<Skin> skins;
    std::vector<Animation> animations;
    // KHR_materials_variants: the names of the asset's material variants, in file order (a
    // VariantId indexes it); empty without the extension. Primitive::variantMaterials maps them.
    std::vector<std::string> variants;
    Bounds bounds;                            // World-space box of all instances.
    std::vector<std::string> extensionsUsed;  // As the file declares them.
    std::vector<std::string> extensionsRequired;
    // Extensions used by the file that Encore does not implement (ignored, optional ones).
    std::vector<std::string> extensionsIgnored;
    std::vector<std::string> warnings;

    // Bytes from the accessor's first element to the end of its last one, in the view's layout
    // (elements are byteStride apart).
    std::span<const std::uint8_t> accessorBytes(AccessorId accessor) const;

    // The accessor's elements copied tightly packed (byteStride == elementSize()).
    std::vector<std::uint8_t> packedAccessorBytes(AccessorId accessor) const;

    // Index values widened to 32 bits.
    std::vector<std::uint32_t> readIndices(AccessorId accessor) const;

    // Elements converted to float (normalized integers mapped to [0,1] or [-1,1]), padded to 4
    // components with (0, 0, 0, 1).
    std::vector<glm::vec4> readFloats(AccessorId accessor) const;

    std::size_t primitiveCount() const;  // Summed over meshes.
    // Triangles the instances draw at full detail, summed over them (a mesh placed twice counts
    // twice): what a rasteriser faces per view.
    std::uint64_t drawnTriangleCount() const;
    // Whether every primitive drawn is a triangle list with an opaque material (alphaMode OPAQUE,
    // no transmission) and no animation of its vertices (no skin on its node, no morph targets),
    // in the default materials; false for a scene that draws nothing. The visibility strategy's
    // compute raster takes all of such a scene; it draws the rest with the graphics pipeline.
    bool drawsOnlyOpaqueStaticTriangles() const;
};

// Triangles drawn by `count` vertices or indices of a topology (0 for points and lines).
std::uint64_t triangleCount(Topology topology, std::uint64_t count);
// The triangles a primitive of `scene` draws: its index count, or its vertex count without one.
std::uint64_t triangleCount(const SceneData& scene, const Primitive& primitive);

// How LoadOptions::optimizeMeshes orders triangles for the post-transform vertex cache
// (MeshOptimizer.h).
enum class VertexCacheOrder : std::uint8_t {
    // meshopt_optimizeVertexCache: the order that suits any cache size best. For models that
    // are loaded once and drawn many times.
    Thorough,
    // meshopt_optimizeVertexCacheFifo with a 16-entry FIFO: 3.4 times faster on the shared
    // models, whose orders then missed a FIFO cache as rarely
    // (docs/benchmarks/2026-11-24-lavapipe-batch-load.md); meshoptimizer rates its orders a
    // little worse in general. For models drawn only a few times each (encore batch).
    Fast,
};

class LoadBudget;  // src/scene/LoadBudget.h: what encore batch shares between its loads.

struct LoadOptions {
    bool decodeImages = true;  // False skips image decoding (images keep their names only).
    bool strict = false;       // Warnings (missing images, unsupported optional features)
                               // become errors.
    // Reorders the triangles and vertices of indexed triangle lists for the GPU's vertex cache
    // and vertex fetch (MeshOptimizer.h); what is drawn stays the same.
    bool optimizeMeshes = true;
    VertexCacheOrder vertexCacheOrder = VertexCacheOrder::Thorough;
    // Builds Primitive::levels (MeshOptimizer.h). Costs load time and memory that only a
    // renderer which selects levels earns back.
    bool buildLevelsOfDetail = true;
    // Groups each level's triangles into clusters (Primitive::clusters, with optimizeMeshes;
    // MeshOptimizer.h), which the visibility strategy culls one by one. Costs load time (a dense
    // model of 265,000 triangles: 0.31 s to load without, 0.66 s with; with VertexCacheOrder::Fast
    // the clusters are scanned in the vertex-cache order instead, at no measurable cost) that
    // only that strategy earns back.
    bool buildClusters = true;
    // With buildClusters: only for a scene that draws at least this many triangles
    // (SceneData::drawnTriangleCount), as encore batch draws only those with the visibility
    // strategy by default (batch::BatchOptions::strategy). 0: for every scene.
    std::uint64_t clustersFromTriangles = 0;
    // With buildClusters: also for a scene of any size that draws only opaque, static triangles
    // (SceneData::drawsOnlyOpaqueStaticTriangles), which encore batch draws with the visibility
    // strategy at four samples by default.
    bool clustersForOpaqueStatic = false;
    // Images with a side longer than this are downscaled while they are decoded (JPEGs decode
    // at a fraction of their size, PNGs too large to decode whole row by row, then every
    // format is box-filtered; Image::sourceWidth keeps the file's size), so one huge texture
    // costs neither the memory nor the upload of its full size. 0: images keep their size.
    std::uint32_t maxImageDimension = 0;
    // External uris (buffers, images) resolve only inside the folder that holds the model file
    // (after percent-decoding, `.`/`..` and symbolic links): an absolute path, a `..` escape or a
    // link that leads out is refused (the buffer fails the model, the image is drawn as missing),
    // so that a model from an untrusted collection cannot read other local files. True: any
    // file the uri names (trusted local trees; encore --allow-uris-outside).
    bool allowUrisOutside = false;
    // > 0: the bytes the model holds decoded (its buffers, decompressed and materialised data and
    // decoded images) may not pass this; the load fails with LimitExceeded at the stage that
    // passes it. Checked as they grow, so a file cannot make the loader take the machine's
    // memory (encore batch sets its --memory-limit). 0: no limit.
    std::uint64_t maxModelBytes = 0;
    // Told what the model holds decoded at each of those checks, and may hold the load there
    // until loads running beside it leave room (src/scene/LoadBudget.h). Null: none.
    LoadBudget* budget = nullptr;
    // Set from another thread to abandon the load: it stops at its next check (between its
    // stages, images and meshes) and fails with LimitExceeded. For callers that give up on a
    // load that takes too long (encore batch --model-timeout).
    const std::atomic<bool>* cancel = nullptr;
};

// Loads a .gltf or .glb file. Errors name the file and the offending element:
// "<file>: accessor 3 (POSITION of mesh 0, primitive 1) reads past the end of bufferView 2
// (offset 4096 + 1200 bytes > length 5000)."
Result<SceneData> loadScene(const std::filesystem::path& path, const LoadOptions& options = {});

// Same, from bytes already in memory (.glb if they start with the GLB magic, JSON otherwise).
// External uris resolve against baseDirectory; displayName prefixes error messages.
Result<SceneData> loadSceneFromMemory(std::span<const std::uint8_t> bytes,
                                      const std::filesystem::path& baseDirectory,
                                      const std::string& displayName,
                                      const LoadOptions& options = {});

// KHR_materials_variants: a file names material variants ("midnight", "beach") and each
// primitive maps some of them to other materials (SceneData::variants,
// Primitive::variantMaterials). Selecting a variant (render::Renderer::selectVariant) changes
// which material each primitive draws, nothing else. These find a variant by name or index and
// read a file's variant names without loading it.

// The variant `nameOrIndex` names among `variants`: an exact name first, else a decimal index.
std::optional<VariantId> findVariant(std::span<const std::string> variants,
                                     std::string_view nameOrIndex);
std::optional<VariantId> findVariant(const SceneData& scene, std::string_view nameOrIndex);

// findVariant, or an InvalidArgument error that names `file` and lists the variants it has:
// "'shoe.glb' has no material variant 'red' (its variants: 0 'midnight', 1 'beach')."
Result<VariantId> resolveVariant(std::span<const std::string> variants,
                                 std::string_view nameOrIndex,
                                 const std::string& file);
Result<VariantId> resolveVariant(const SceneData& scene, std::string_view nameOrIndex);

// "0 'midnight', 1 'beach'", or "none".
std::string describeVariants(std::span<const std::string> variants);

// The variant names a .gltf or .glb declares, read from its JSON alone (not a .glb's binary
// chunk, not the buffers): what encore batch reads to know a model's samples before loading it.
// Errors name the file; a file that loads has the same names in SceneData::variants.
Result<std::vector<std::string>> readVariantNames(const std::filesystem::path& path);

}  // namespace encore::scene
