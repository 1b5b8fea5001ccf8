#pragma once

// The state shared by the loader's stages, and the stages themselves in the order SceneLoader.cpp
// runs them. Each stage reads the parsed GltfDocument and fills part of the SceneData; errors it
// returns name the glTF element but not the file (SceneLoader adds the file's display name).

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "encore/scene/SceneData.h"
#include "scene/GltfDocument.h"

namespace encore::scene {

// Accessors without a bufferView, sparse accessors and decompressed data are materialised into
// new buffers; one materialisation larger than this is refused as LimitExceeded.
inline constexpr std::uint64_t kMaxMaterializedBytes = std::uint64_t{1} << 30;

// dracoRemaps key for the indices Draco decoded for a primitive that declares no indices accessor.
inline constexpr std::uint32_t kDracoIndicesKey = 0xFFFFFFFFu;

// Where a model's external uris may lead: inside `folder` (the model file's), after
// percent-decoding, `.`/`..` and symbolic links are resolved, unless `allowOutside`
// (LoadOptions::allowUrisOutside).
struct UriScope {
    std::filesystem::path folder;
    bool allowOutside = false;
};

struct LoadContext {
    std::string displayName;
    std::filesystem::path baseDirectory;
    LoadOptions options;
    GltfDocument document;
    std::optional<std::span<const std::uint8_t>> glbBinChunk;
    SceneData scene;

    // How each glTF accessor is first used ("POSITION of mesh 0, primitive 1"), for messages.
    std::vector<std::string> accessorUses;
    // Accessors whose every use is by a Draco-compressed primitive: their data comes from Draco.
    std::vector<bool> accessorDracoOnly;
    // scene.accessors slots already filled (by Draco) before resolveAccessors runs.
    std::vector<bool> accessorFilled;
    // Per Draco primitive (mesh, primitive): glTF accessor index → decoded accessor, for the
    // rare accessor that two Draco primitives share and so cannot be decoded in place.
    std::map<std::pair<std::size_t, std::size_t>, std::unordered_map<std::uint32_t, AccessorId>>
        dracoRemaps;
    // Legal copies of vertex attributes, by (accessor, semantic), shared between primitives.
    std::map<std::pair<std::uint32_t, Semantic>, AccessorId> legalCopies;
    // Float32 copies of integer morph target accessors, by accessor, shared between primitives.
    std::map<AccessorId, AccessorId> morphCopies;
    // The image each glTF texture draws, as loadImages chose it: EXT_texture_webp's image when
    // it decodes, else the core source (nullopt: none).
    std::vector<std::optional<std::uint32_t>> textureImages;

    // "accessor 3 (POSITION of mesh 0, primitive 1)" or "accessor 3".
    std::string accessorName(std::size_t index) const;
    // Records "<displayName>: <message>" as a warning and logs it; in strict mode returns it as
    // an error with `code` instead.
    Result<void> warn(ErrorCode code, std::string message);
    // Fails once LoadOptions::cancel is set: the stages check between their long steps.
    Result<void> checkCancelled() const;
    UriScope uriScope() const { return {baseDirectory, options.allowUrisOutside}; }
    // Fails once the scene's buffers and decoded images hold more than
    // LoadOptions::maxModelBytes, naming `stage`; else tells LoadOptions::budget what they hold.
    Result<void> checkModelBytes(std::string_view stage) const;
};

// GlbContainer.cpp ---------------------------------------------------------------------------
struct GlbChunks {
    std::span<const std::uint8_t> json;
    std::optional<std::span<const std::uint8_t>> bin;
};
bool hasGlbMagic(std::span<const std::uint8_t> bytes);
// Validates the header and every chunk length against the bytes.
Result<GlbChunks> parseGlb(std::span<const std::uint8_t> bytes);

// UriResolver.cpp ----------------------------------------------------------------------------
std::string percentDecode(std::string_view text);
bool isDataUri(std::string_view uri);
// base64 or percent-encoded payload of a data: uri.
Result<std::vector<std::uint8_t>> decodeDataUri(std::string_view uri);
// The file a relative uri names; an error for uris with a scheme other than data: (http: ...),
// and for files outside the scope's folder (absolute paths, `..` escapes, symbolic links that
// lead out).
Result<std::filesystem::path> resolveUriPath(std::string_view uri, const UriScope& scope);
// Reads a data: uri or the regular file a relative uri names (no FIFOs, devices, sockets).
Result<std::vector<std::uint8_t>> readUri(std::string_view uri, const UriScope& scope);
// Fills scene.buffers: GLB BIN chunk, data: uris, external files; meshopt fallbacks stay empty.
Result<void> loadBuffers(LoadContext& context);

// Validation.cpp -----------------------------------------------------------------------------
// Every index in the document names an existing element.
Result<void> validateReferences(const GltfDocument& document);
// Fills scene.bufferViews, checking ranges and strides (meshopt views are decoded after).
Result<void> buildBufferViews(LoadContext& context);
// Records accessorUses and accessorDracoOnly.
void labelAccessorUses(LoadContext& context);
// a * b + c, or nullopt on 64-bit overflow.
std::optional<std::uint64_t> mulAdd(std::uint64_t a, std::uint64_t b, std::uint64_t c);

// MeshoptDecoder.cpp -------------------------------------------------------------------------
// Decodes EXT_meshopt_compression views into new buffers and points the views at them.
Result<void> decodeMeshoptViews(LoadContext& context);

// DracoDecoder.cpp ---------------------------------------------------------------------------
Result<void> decodeDracoPrimitives(LoadContext& context);

// AccessorMaterializer.cpp -------------------------------------------------------------------
// Appends a buffer, a view and a tightly packed accessor holding `bytes`.
AccessorId appendAccessor(SceneData& scene,
                          std::vector<std::uint8_t> bytes,
                          ComponentType componentType,
                          std::uint8_t componentCount,
                          bool normalized,
                          std::uint32_t count,
                          std::string bufferName);
// Fills every scene.accessors slot not filled yet: range checks, sparse and zero data.
Result<void> resolveAccessors(LoadContext& context);

// AttributeLegalizer.cpp ---------------------------------------------------------------------
std::optional<Semantic> semanticFromName(std::string_view name);
// The accessor itself when WebGPU can bind it as is, otherwise a repacked or float copy.
Result<AccessorId> legalizeAttribute(LoadContext& context,
                                     Semantic semantic,
                                     AccessorId accessor,
                                     const std::string& what);
// The elements of `accessor` at `corners`, tightly packed, as a new accessor.
AccessorId gatherAccessor(SceneData& scene,
                          AccessorId accessor,
                          std::span<const std::uint32_t> corners,
                          const std::string& name);

// PrimitiveConverter.cpp ---------------------------------------------------------------------
Result<void> convertMeshes(LoadContext& context);

// MaterialVariants.cpp -----------------------------------------------------------------------
// A primitive's KHR_materials_variants mappings (references already validated), sorted by
// variant; `name` ("mesh 0, primitive 1") names it when a variant is mapped twice.
Result<std::vector<VariantMapping>> convertVariantMappings(const GltfPrimitive& primitive,
                                                           const std::string& name);

// MaterialParser.cpp -------------------------------------------------------------------------
// Fills scene.materials, textures and samplers (images are loaded separately).
Result<void> convertMaterials(LoadContext& context);
// The index of the glTF default material, appended on first use.
MaterialId defaultMaterial(SceneData& scene);

// ImageLoader.cpp ----------------------------------------------------------------------------
// Decodes the images the textures draw (EXT_texture_webp's when it decodes, else the core
// source; never KHR_texture_basisu's) and those no texture uses, and fills textureImages.
Result<void> loadImages(LoadContext& context);

// NodeHierarchy.cpp --------------------------------------------------------------------------
// Fills scene.nodes with world matrices, the instances of the chosen scene and scene.bounds.
Result<void> buildNodes(LoadContext& context);

// SkinsAnimations.cpp ------------------------------------------------------------------------
// Fills scene.skins (after buildNodes) and checks the joint indices of skinned primitives.
Result<void> convertSkins(LoadContext& context);
// Fills scene.animations: samplers decoded, channels checked against nodes and meshes.
Result<void> convertAnimations(LoadContext& context);

}  // namespace encore::scene
