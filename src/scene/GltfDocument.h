#pragma once

// The glTF JSON as plain structs: what the file says, typed but not yet cross-checked. Indices
// are raw glTF indices; Validation.cpp checks that each one names an existing element, and the
// later stages turn the structs into SceneData.

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "encore/scene/SceneData.h"
#include "scene/GltfJson.h"

namespace encore::scene {

// glTF componentType enums.
inline constexpr std::uint32_t kGlByte = 5120;
inline constexpr std::uint32_t kGlUnsignedByte = 5121;
inline constexpr std::uint32_t kGlShort = 5122;
inline constexpr std::uint32_t kGlUnsignedShort = 5123;
inline constexpr std::uint32_t kGlUnsignedInt = 5125;
inline constexpr std::uint32_t kGlFloat = 5126;

struct GltfBuffer {
    std::optional<std::string> uri;
    std::uint64_t byteLength = 0;
    bool meshoptFallback = false;  // EXT_meshopt_compression: never loaded.
};

struct GltfMeshoptCompression {
    std::uint32_t buffer = 0;
    std::uint64_t byteOffset = 0;
    std::uint64_t byteLength = 0;
    std::uint32_t byteStride = 0;
    std::uint64_t count = 0;
    std::string mode;  // ATTRIBUTES, TRIANGLES or INDICES.
    std::string filter = "NONE";
};

struct GltfBufferView {
    std::uint32_t buffer = 0;
    std::uint64_t byteOffset = 0;
    std::uint64_t byteLength = 0;
    std::optional<std::uint64_t> byteStride;
    std::optional<GltfMeshoptCompression> meshopt;
};

struct GltfSparse {
    std::uint64_t count = 0;
    std::uint32_t indicesView = 0;
    std::uint64_t indicesOffset = 0;
    std::uint32_t indicesComponentType = 0;
    std::uint32_t valuesView = 0;
    std::uint64_t valuesOffset = 0;
};

struct GltfAccessor {
    std::optional<std::uint32_t> bufferView;
    std::uint64_t byteOffset = 0;
    std::uint64_t count = 0;
    ComponentType componentType = ComponentType::Float32;
    std::uint32_t glComponentType = kGlFloat;
    std::string type;                  // SCALAR, VEC2..4, MAT2..4.
    std::uint32_t componentCount = 1;  // 1..4, or 4/9/16 for matrices.
    bool isMatrix = false;
    bool normalized = false;
    std::vector<float> min;
    std::vector<float> max;
    std::optional<GltfSparse> sparse;
};

using AttributeMap = std::vector<std::pair<std::string, std::uint32_t>>;

struct GltfDracoCompression {
    std::uint32_t bufferView = 0;
    AttributeMap attributes;  // Semantic → Draco unique attribute id.
};

// KHR_materials_variants: the material a primitive draws under `variants`.
struct GltfVariantMapping {
    std::uint32_t material = 0;
    std::vector<std::uint32_t> variants;  // Indices into GltfDocument::variants; at least one.
};

struct GltfPrimitive {
    AttributeMap attributes;  // Semantic → accessor, in file order.
    std::optional<std::uint32_t> indices;
    std::optional<std::uint32_t> material;
    std::uint32_t mode = 4;
    std::optional<GltfDracoCompression> draco;
    std::vector<AttributeMap> targets;                // Morph targets.
    std::vector<GltfVariantMapping> variantMappings;  // KHR_materials_variants, as written.
};

struct GltfMesh {
    std::string name;
    std::vector<GltfPrimitive> primitives;
    std::optional<std::vector<float>> weights;  // Default morph weights.
};

struct GltfInstancing {
    std::optional<std::uint32_t> translation;
    std::optional<std::uint32_t> rotation;
    std::optional<std::uint32_t> scale;
};

struct GltfNode {
    std::string name;
    std::vector<std::uint32_t> children;
    std::optional<std::uint32_t> mesh;
    std::optional<std::uint32_t> skin;
    std::optional<std::uint32_t> camera;
    std::optional<std::uint32_t> light;  // KHR_lights_punctual.
    glm::mat4 local{1.0f};
    // TRS as written (defaults when absent); with a matrix, its decomposition.
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // Normalised (identity when of zero length).
    glm::vec3 scale{1.0f};
    bool hasMatrix = false;
    std::optional<std::vector<float>> weights;  // Morph weights overriding the mesh's.
    std::optional<GltfInstancing> instancing;
};

struct GltfTextureInfo {
    std::uint32_t index = 0;
    std::uint32_t texCoord = 0;
    std::optional<TextureTransform> transform;
    float scale = 1.0f;  // normalTexture.scale / occlusionTexture.strength.
};

// Material extensions as written; textures stay raw glTF references until validated.
struct GltfSpecular {
    float specularFactor = 1.0f;
    std::optional<GltfTextureInfo> specularTexture;
    glm::vec3 specularColorFactor{1.0f};
    std::optional<GltfTextureInfo> specularColorTexture;
};

struct GltfClearcoat {
    float clearcoatFactor = 0.0f;
    std::optional<GltfTextureInfo> clearcoatTexture;
    float clearcoatRoughnessFactor = 0.0f;
    std::optional<GltfTextureInfo> clearcoatRoughnessTexture;
    std::optional<GltfTextureInfo> clearcoatNormalTexture;  // scale: its 'scale'.
};

struct GltfSheen {
    glm::vec3 sheenColorFactor{0.0f};
    std::optional<GltfTextureInfo> sheenColorTexture;
    float sheenRoughnessFactor = 0.0f;
    std::optional<GltfTextureInfo> sheenRoughnessTexture;
};

struct GltfSpecularGlossiness {
    glm::vec4 diffuseFactor{1.0f};
    std::optional<GltfTextureInfo> diffuseTexture;
    glm::vec3 specularFactor{1.0f};
    float glossinessFactor = 1.0f;
    std::optional<GltfTextureInfo> specularGlossinessTexture;
};

struct GltfIridescence {
    float iridescenceFactor = 0.0f;
    std::optional<GltfTextureInfo> iridescenceTexture;
    float iridescenceIor = 1.3f;
    float iridescenceThicknessMinimum = 100.0f;
    float iridescenceThicknessMaximum = 400.0f;
    std::optional<GltfTextureInfo> iridescenceThicknessTexture;
};

struct GltfAnisotropy {
    float anisotropyStrength = 0.0f;
    float anisotropyRotation = 0.0f;
    std::optional<GltfTextureInfo> anisotropyTexture;
};

struct GltfTransmission {
    float transmissionFactor = 0.0f;
    std::optional<GltfTextureInfo> transmissionTexture;
};

struct GltfVolume {
    float thicknessFactor = 0.0f;
    std::optional<GltfTextureInfo> thicknessTexture;
    float attenuationDistance = std::numeric_limits<float>::infinity();
    glm::vec3 attenuationColor{1.0f};
};

struct GltfDiffuseTransmission {
    float diffuseTransmissionFactor = 0.0f;
    std::optional<GltfTextureInfo> diffuseTransmissionTexture;
    glm::vec3 diffuseTransmissionColorFactor{1.0f};
    std::optional<GltfTextureInfo> diffuseTransmissionColorTexture;
};

struct GltfMaterial {
    std::string name;
    glm::vec4 baseColorFactor{1.0f};
    std::optional<GltfTextureInfo> baseColorTexture;
    float metallicFactor = 1.0f;
    float roughnessFactor = 1.0f;
    std::optional<GltfTextureInfo> metallicRoughnessTexture;
    std::optional<GltfTextureInfo> normalTexture;
    std::optional<GltfTextureInfo> occlusionTexture;
    std::optional<GltfTextureInfo> emissiveTexture;
    glm::vec3 emissiveFactor{0.0f};
    std::string alphaMode = "OPAQUE";
    float alphaCutoff = 0.5f;
    bool doubleSided = false;
    float emissiveStrength = 1.0f;
    bool unlit = false;
    float ior = 1.5f;
    std::optional<GltfSpecular> specular;
    std::optional<GltfClearcoat> clearcoat;
    std::optional<GltfSheen> sheen;
    std::optional<GltfSpecularGlossiness> specularGlossiness;
    std::optional<GltfIridescence> iridescence;
    std::optional<GltfAnisotropy> anisotropy;
    std::optional<GltfTransmission> transmission;
    std::optional<GltfVolume> volume;
    std::optional<float> dispersion;
    std::optional<GltfDiffuseTransmission> diffuseTransmission;
    std::vector<std::string> ignoredExtensions;  // Extension objects Encore does not shade.
};

// One texture reference of a material, named as messages name it ("normalTexture",
// "KHR_materials_clearcoat clearcoatTexture").
struct GltfMaterialTextureSlot {
    std::string slot;
    const GltfTextureInfo* info;
};

// Every texture reference the material holds, core slots first; absent ones are left out.
std::vector<GltfMaterialTextureSlot> materialTextureSlots(const GltfMaterial& material);

struct GltfTexture {
    std::optional<std::uint32_t> source;
    std::optional<std::uint32_t> sampler;
    std::optional<std::uint32_t> webpSource;    // EXT_texture_webp: preferred to `source`.
    std::optional<std::uint32_t> basisuSource;  // KHR_texture_basisu: never decoded.
};

struct GltfImage {
    std::string name;
    std::optional<std::string> uri;
    std::optional<std::uint32_t> bufferView;
    std::string mimeType;
};

struct GltfSampler {
    std::optional<std::uint64_t> magFilter;
    std::optional<std::uint64_t> minFilter;
    std::uint64_t wrapS = 10497;
    std::uint64_t wrapT = 10497;
};

struct GltfSkin {
    std::string name;
    std::optional<std::uint32_t> inverseBindMatrices;
    std::vector<std::uint32_t> joints;
    std::optional<std::uint32_t> skeleton;
};

struct GltfAnimationChannel {
    std::uint32_t sampler = 0;
    std::optional<std::uint32_t> node;  // Absent: targeted by an extension (ignored).
    std::string path;
};

struct GltfAnimationSampler {
    std::uint32_t input = 0;
    std::uint32_t output = 0;
    std::string interpolation = "LINEAR";
};

struct GltfAnimation {
    std::string name;
    double timeOffset = 0.0;  // extras.encoreTimeOffset (see scene::Animation::timeOffset).
    std::vector<GltfAnimationChannel> channels;
    std::vector<GltfAnimationSampler> samplers;
};

struct GltfDocument {
    std::string version;
    std::vector<std::string> extensionsUsed;
    std::vector<std::string> extensionsRequired;
    std::vector<GltfBuffer> buffers;
    std::vector<GltfBufferView> bufferViews;
    std::vector<GltfAccessor> accessors;
    std::vector<GltfMesh> meshes;
    std::vector<GltfNode> nodes;
    std::vector<GltfMaterial> materials;
    std::vector<GltfTexture> textures;
    std::vector<GltfImage> images;
    std::vector<GltfSampler> samplers;
    std::vector<GltfSkin> skins;
    std::vector<GltfAnimation> animations;
    std::vector<CameraData> cameras;
    std::vector<Light> lights;                       // KHR_lights_punctual.
    std::vector<std::string> variants;               // KHR_materials_variants names.
    std::vector<std::vector<std::uint32_t>> scenes;  // Root nodes of each scene.
    std::optional<std::uint32_t> scene;
};

// Reads the whole document. Type errors name the element ("accessor 3 has an invalid 'count'
// (expected a non-negative integer, got "three")."); asset.version and extensionsRequired are
// checked here too.
Result<GltfDocument> parseDocument(const Json& root);

// Reads materials, textures, images and samplers (MaterialParser.cpp).
Result<void> parseMaterialElements(const Json& root, GltfDocument& document);

// Reads cameras and KHR_lights_punctual lights, checking their values (LightsCameras.cpp).
Result<void> parseLightsAndCameras(const Json& root, GltfDocument& document);

// Reads animations (SkinsAnimations.cpp).
Result<void> parseAnimations(const Json& root, GltfDocument& document);

// Extensions Encore implements; a required extension outside this list is refused.
bool isSupportedExtension(std::string_view name);

// KHR_materials_variants (MaterialVariants.cpp): the root's variant names (empty without the
// extension), and a primitive's mappings (errors recorded in `primitive`).
Result<std::vector<std::string>> parseVariantNames(const Json& root);
std::vector<GltfVariantMapping> readVariantMappings(FieldReader& primitive, const Json& extension);

// Material extensions the loader reads; any other extension object on a material is ignored.
inline constexpr std::array kShadedMaterialExtensions = {
    std::string_view("KHR_materials_emissive_strength"),
    std::string_view("KHR_materials_unlit"),
    std::string_view("KHR_materials_ior"),
    std::string_view("KHR_materials_specular"),
    std::string_view("KHR_materials_clearcoat"),
    std::string_view("KHR_materials_sheen"),
    std::string_view("KHR_materials_pbrSpecularGlossiness"),
    std::string_view("KHR_materials_iridescence"),
    std::string_view("KHR_materials_anisotropy"),
    std::string_view("KHR_materials_transmission"),
    std::string_view("KHR_materials_volume"),
    std::string_view("KHR_materials_dispersion"),
    std::string_view("KHR_materials_diffuse_transmission"),
};

}  // namespace encore::scene
