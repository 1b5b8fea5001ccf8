// loadScene: reads the container (.gltf JSON or .glb), parses the document and runs the stages
// of LoadContext.h in order. Stage errors name the element; the file's display name is added
// here, once, so every message reads "<file>: <sentence>".

#include <algorithm>
#include <exception>
#include <new>

#include "core/FileIO.h"
#include "core/Log.h"
#include "scene/LoadBudget.h"
#include "scene/LoadContext.h"
#include "scene/MeshOptimizer.h"

namespace encore::scene {
namespace {

// Deeper JSON than this is refused before parsing: glTF needs a handful of levels, and although
// nlohmann's parser and destructor iterate, copying or printing a value recurses once per level.
constexpr std::size_t kMaxJsonDepth = 512;

// More values than this are refused before parsing: the parsed document takes about 50 bytes
// a value, so a few hundred megabytes of `[0,0,...]` would take gigabytes; a glTF asset keeps
// its bulk data in buffers, and the largest scene graphs hold a few million values.
constexpr std::size_t kMaxJsonValues = 10'000'000;

struct JsonShape {
    std::size_t deepest = 0;  // Nesting of arrays and objects.
    std::size_t values = 0;   // About: commas and openings, outside strings.
};

// The shape of `text` (brackets and commas inside strings do not count), stopping early once it
// passes kMaxJsonDepth or kMaxJsonValues.
JsonShape jsonShape(std::span<const std::uint8_t> text) {
    std::size_t depth = 0;
    std::size_t deepest = 0;
    std::size_t values = 0;
    bool inString = false;
    for (std::size_t i = 0; i < text.size() && deepest <= kMaxJsonDepth && values <= kMaxJsonValues;
         ++i) {
        const std::uint8_t c = text[i];
        if (inString) {
            if (c == '\\') {
                ++i;  // Skips the escaped character (a quote or another backslash).
            } else if (c == '"') {
                inString = false;
            }
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            deepest = std::max(deepest, ++depth);
            ++values;
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        } else if (c == ',') {
            ++values;
        }
    }
    return {deepest, values};
}

// More elements of one kind than this (nodes, meshes, accessors, ...; primitives summed over the
// meshes) are refused before the scene is built: each costs the loader a few hundred bytes, and
// the largest assets hold a few hundred thousand nodes.
constexpr std::size_t kMaxElementsOfAKind = 1'000'000;

Result<void> checkElementCounts(const Json& root) {
    const auto refuse = [](std::size_t count, const std::string& kind) {
        return makeError(ErrorCode::LimitExceeded, "The glTF holds " + std::to_string(count) + " " +
                                                       kind + ", more than Encore's limit of " +
                                                       std::to_string(kMaxElementsOfAKind) + ".");
    };
    if (!root.is_object()) {
        return {};  // parseDocument says what is wrong with it.
    }
    for (const auto& [kind, elements] : root.items()) {
        if (elements.is_array() && elements.size() > kMaxElementsOfAKind) {
            return refuse(elements.size(), kind);
        }
    }
    std::size_t primitives = 0;
    if (const auto meshes = root.find("meshes"); meshes != root.end() && meshes->is_array()) {
        for (const Json& mesh : *meshes) {
            const auto found = mesh.is_object() ? mesh.find("primitives") : mesh.end();
            primitives += found != mesh.end() && found->is_array() ? found->size() : 0;
        }
    }
    if (primitives > kMaxElementsOfAKind) {
        return refuse(primitives, "primitives");
    }
    return {};
}

Result<Json> parseJson(std::span<const std::uint8_t> text) {
    // A UTF-8 byte order mark is not JSON but some exporters write one.
    if (text.size() >= 3 && text[0] == 0xEF && text[1] == 0xBB && text[2] == 0xBF) {
        text = text.subspan(3);
    }
    // GLB JSON chunks are padded with spaces; some writers pad with NULs, which JSON forbids.
    while (!text.empty() && text.back() == 0) {
        text = text.first(text.size() - 1);
    }
    if (text.empty()) {
        return makeError(ErrorCode::InvalidFormat,
                         "The file is empty (0 bytes of glTF JSON); it holds no asset.");
    }
    const JsonShape shape = jsonShape(text);
    if (shape.deepest > kMaxJsonDepth) {
        return makeError(ErrorCode::LimitExceeded,
                         "The glTF JSON nests arrays and objects more than " +
                             std::to_string(kMaxJsonDepth) +
                             " levels deep; Encore refuses it (no glTF asset needs that depth).");
    }
    if (shape.values > kMaxJsonValues) {
        return makeError(ErrorCode::LimitExceeded,
                         "The glTF JSON holds more than " + std::to_string(kMaxJsonValues) +
                             " values; Encore refuses it before parsing (glTF keeps bulk data in "
                             "buffers, not in its JSON).");
    }
    try {
        return Json::parse(text.begin(), text.end());
    } catch (const Json::parse_error& error) {
        // nlohmann's message already says where: "parse error at line 3, column 5: ...".
        return makeError(ErrorCode::InvalidFormat, "The glTF JSON is invalid (" +
                                                       std::string(error.what()) + ", byte " +
                                                       std::to_string(error.byte) + ").");
    }
}

// Copies the declared extensions into the scene and warns once per used extension Encore does
// not implement (parseDocument already refused required ones).
Result<void> recordExtensions(LoadContext& context) {
    SceneData& scene = context.scene;
    scene.extensionsUsed = context.document.extensionsUsed;
    scene.extensionsRequired = context.document.extensionsRequired;
    for (const std::string& extension : scene.extensionsUsed) {
        if (isSupportedExtension(extension) ||
            std::find(scene.extensionsIgnored.begin(), scene.extensionsIgnored.end(), extension) !=
                scene.extensionsIgnored.end()) {
            continue;
        }
        scene.extensionsIgnored.push_back(extension);
        const bool material =
            extension.starts_with("KHR_materials_") || extension.starts_with("EXT_materials_");
        ENCORE_TRY(context.warn(
            ErrorCode::Unsupported,
            "The asset uses " + extension + ", which Encore does not implement; " +
                (material ? "materials are drawn without it." : "the asset is drawn without it.")));
    }
    return {};
}

Result<SceneData> load(std::span<const std::uint8_t> bytes, LoadContext& context) {
    std::span<const std::uint8_t> jsonText = bytes;
    // A .glb without the magic gets the GLB error, not a confusing JSON one.
    const bool glbName =
        context.displayName.size() >= 4 &&
        context.displayName.compare(context.displayName.size() - 4, 4, ".glb") == 0;
    if (hasGlbMagic(bytes) || glbName) {
        GlbChunks chunks;
        ENCORE_TRY_ASSIGN(chunks, parseGlb(bytes));
        jsonText = chunks.json;
        context.glbBinChunk = chunks.bin;
    }
    Json root;
    ENCORE_TRY_ASSIGN(root, parseJson(jsonText));
    ENCORE_TRY(checkElementCounts(root));
    ENCORE_TRY_ASSIGN(context.document, parseDocument(root));
    root = Json();  // The document holds everything needed; free the DOM early.

    ENCORE_TRY(context.checkCancelled());
    ENCORE_TRY(validateReferences(context.document));
    ENCORE_TRY(recordExtensions(context));
    ENCORE_TRY(loadBuffers(context));
    ENCORE_TRY(context.checkModelBytes("reading its buffers"));
    ENCORE_TRY(buildBufferViews(context));
    ENCORE_TRY(decodeMeshoptViews(context));
    labelAccessorUses(context);
    ENCORE_TRY(context.checkCancelled());
    ENCORE_TRY(decodeDracoPrimitives(context));
    ENCORE_TRY(resolveAccessors(context));
    ENCORE_TRY(context.checkModelBytes("decoding its compressed and sparse data"));
    ENCORE_TRY(context.checkCancelled());
    ENCORE_TRY(loadImages(context));
    ENCORE_TRY(convertMaterials(context));
    ENCORE_TRY(context.checkCancelled());
    ENCORE_TRY(convertMeshes(context));
    ENCORE_TRY(context.checkCancelled());
    ENCORE_TRY(buildNodes(context));
    ENCORE_TRY(convertSkins(context));
    ENCORE_TRY(convertAnimations(context));
    ENCORE_TRY(context.checkCancelled());
    // Last: it rewrites the index and vertex data every stage above has checked.
    MeshOptimizerOptions meshOptions;
    meshOptions.optimizeVertexOrder = context.options.optimizeMeshes;
    meshOptions.vertexCacheOrder = context.options.vertexCacheOrder;
    meshOptions.buildLevelsOfDetail = context.options.buildLevelsOfDetail;
    meshOptions.buildClusters =
        context.options.buildClusters &&
        (context.scene.drawnTriangleCount() >= context.options.clustersFromTriangles ||
         (context.options.clustersForOpaqueStatic &&
          context.scene.drawsOnlyOpaqueStaticTriangles()));
    ENCORE_TRY(optimizeMeshes(context.scene, meshOptions));
    return std::move(context.scene);
}

}  // namespace

std::string LoadContext::accessorName(std::size_t index) const {
    std::string name = "accessor " + std::to_string(index);
    if (index < accessorUses.size() && !accessorUses[index].empty()) {
        name += " (" + accessorUses[index] + ")";
    }
    return name;
}

Result<void> LoadContext::warn(ErrorCode code, std::string message) {
    if (options.strict) {
        return makeError(code, std::move(message));
    }
    std::string warning = displayName + ": " + message;
    logWarning(warning);
    scene.warnings.push_back(std::move(warning));
    return {};
}

Result<void> LoadContext::checkModelBytes(std::string_view stage) const {
    if (options.maxModelBytes == 0 && options.budget == nullptr) {
        return {};
    }
    const std::uint64_t bytes = decodedBytes(scene);
    if (options.maxModelBytes == 0 || bytes <= options.maxModelBytes) {
        return options.budget ? options.budget->holding(bytes) : Result<void>{};
    }
    return makeError(ErrorCode::LimitExceeded,
                     "The model holds " + std::to_string(bytes) + " bytes of buffers and decoded " +
                         "images after " + std::string(stage) + ", more than its limit of " +
                         std::to_string(options.maxModelBytes) + " bytes (--memory-limit).");
}

Result<void> LoadContext::checkCancelled() const {
    if (options.cancel && options.cancel->load(std::memory_order_relaxed)) {
        return makeError(ErrorCode::LimitExceeded, "Loading was cancelled (it took too long).");
    }
    return {};
}

Result<SceneData> loadScene(const std::filesystem::path& path, const LoadOptions& options) {
    auto bytes = readFile(path);
    if (!bytes.ok()) {
        return bytes.error().withContext(path.string());
    }
    auto result = loadSceneFromMemory(*bytes, path.parent_path(), path.string(), options);
    if (result.ok()) {
        result->sourcePath = path;
    }
    return result;
}

Result<SceneData> loadSceneFromMemory(std::span<const std::uint8_t> bytes,
                                      const std::filesystem::path& baseDirectory,
                                      const std::string& displayName,
                                      const LoadOptions& options) {
    LoadContext context;
    context.displayName = displayName;
    context.baseDirectory = baseDirectory;
    context.options = options;
    try {
        auto result = load(bytes, context);
        if (!result.ok()) {
            return result.error().withContext(displayName);
        }
        result->sourcePath = displayName;  // loadScene replaces it with the real path.
        return result;
    } catch (const std::bad_alloc&) {
        return makeError(ErrorCode::LimitExceeded,
                         displayName + ": Loading ran out of memory (the asset is too large).");
    } catch (const std::exception& exception) {
        // Nothing above should throw on bad input; this keeps the API's no-throw promise if a
        // library does anyway.
        return makeError(ErrorCode::InvalidFormat,
                         displayName + ": Loading failed (" + std::string(exception.what()) + ").");
    }
}

}  // namespace encore::scene
