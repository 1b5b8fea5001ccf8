#pragma once

// OUT/<name>/metadata.json: what a model's file holds and how its rendering went, the record the
// Objaverse-XL scripts keep per object (polygon count, missing textures, bounding box, sha256)
// and more: counts, the images that could not be read, the extensions used and ignored, the
// animations, the views that came out blank (the "some objects render blank" of Cap3D) and the
// time each stage took.
//
// The facts about the file are gathered where it is loaded (on the batch's pool): the file is
// read once, hashed, then parsed from memory.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "encore/batch/BatchInputs.h"
#include "encore/core/Result.h"
#include "encore/scene/SceneData.h"

namespace encore::batch {

inline constexpr const char* kMetadataFileName = "metadata.json";

struct ModelFacts {
    std::uint64_t fileBytes = 0;
    std::string sha256;  // Of the file as read (64 hex digits); empty when it could not be read.

    // As drawn: summed over the instances of the chosen scene (a mesh placed twice counts
    // twice). Triangles of triangle lists and strips; points and lines add none.
    std::uint64_t triangles = 0;
    std::uint64_t vertices = 0;
    std::size_t meshes = 0;
    std::size_t primitives = 0;
    std::size_t instances = 0;
    std::size_t nodes = 0;
    std::size_t materials = 0;  // The file's (not the default one the loader adds).
    std::size_t textures = 0;
    std::size_t images = 0;
    std::size_t lights = 0;
    std::size_t cameras = 0;
    std::size_t skins = 0;

    struct FailedImage {
        std::size_t index = 0;
        std::string name;   // Its uri, or "image N" for embedded ones.
        std::string error;  // Why it could not be read (the loader's warning).
    };
    // Images missing or undecodable: drawn with a default texture (failed with --strict).
    std::vector<FailedImage> imagesFailed;
    // Images larger than BatchOptions::maxTextureSize, downscaled while loading.
    struct DownscaledImage {
        std::size_t index = 0;
        std::string name;
        std::uint32_t originalWidth = 0;  // As the file declares.
        std::uint32_t originalHeight = 0;
        std::uint32_t width = 0;  // As drawn.
        std::uint32_t height = 0;
    };
    std::vector<DownscaledImage> imagesDownscaled;
    std::vector<std::string> extensionsUsed;
    std::vector<std::string> extensionsRequired;
    std::vector<std::string> extensionsIgnored;  // Used by the file, not implemented.
    std::vector<std::string> warnings;

    scene::Bounds bounds;  // World space, before normalisation.
    struct AnimationFacts {
        std::string name;
        float seconds = 0.0f;  // The last key time.
        std::size_t channels = 0;
    };
    std::vector<AnimationFacts> animations;
};

// Seconds each stage spent on the model: loading (reading, hashing, parsing and decoding, on the
// pool), preparing its GPU scene (Renderer::prepare) and recording its views (the device thread,
// without its waits for the GPU), encoding and writing its images (the pool, summed over them).
struct ModelTimes {
    double load = 0.0;
    double upload = 0.0;
    double render = 0.0;
    double encode = 0.0;
};

// How the device thread drew the model: the strategy (BatchOptions::strategy, or auto's choice
// for it) and what it created in the driver for the model (gpu::CreationCounts): GPU objects
// that hold memory (buffers, textures, query sets) and bytes of mappable buffers, zero once the
// lane's pools and renderers have what the models need (issue 48).
struct ModelDrawing {
    std::string strategy;
    std::uint64_t objectsCreated = 0;
    std::uint64_t bytesMapped = 0;
};

// Loads `path` as scene::loadScene does, with the same errors, and fills `facts` with its size
// and SHA-256 (when it could be read) and, once loaded, describeModel's counts.
Result<scene::SceneData> loadModelFile(const std::filesystem::path& path,
                                       const scene::LoadOptions& options,
                                       ModelFacts& facts);

// Fills the counts, lists and bounds of `facts` from a loaded scene.
void describeModel(const scene::SceneData& scene, ModelFacts& facts);

// Pixels of RGBA8 `pixels` (straight alpha) whose alpha is not 0.
std::uint64_t coveredPixels(std::span<const std::uint8_t> pixels);

// The views with fewer than `threshold` covered pixels, in order.
std::vector<std::uint32_t> blankViews(std::span<const std::uint64_t> coveredPixels,
                                      std::uint32_t threshold);

// The contents of metadata.json (`strategy` and `gpu` from `drawing`; `camera`, when not null,
// as "camera": how the views project and the axes their written matrices are in). `coveredPixels`
// has one count per view, or is empty when the views' coverage was not counted (a background that
// is not transparent): blankViews is then null.
nlohmann::json metadataJson(const BatchInput& input,
                            const ModelFacts& facts,
                            const ModelTimes& times,
                            std::uint32_t views,
                            std::span<const std::uint64_t> coveredPixels,
                            std::uint32_t blankThreshold,
                            const ModelDrawing& drawing = {},
                            const nlohmann::json& camera = nullptr);

}  // namespace encore::batch
