#pragma once

// The summary `encore info MODEL` prints: what the loader made of a model (counts, extensions
// and whether Encore shades or ignores them, material extensions left out, material variants,
// KTX2 images it cannot decode, warnings), computed from SceneData alone so no GPU device is
// needed.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "encore/scene/SceneData.h"

namespace encore::scene {

struct ModelCounts {
    std::size_t meshes = 0;
    std::size_t primitives = 0;
    std::uint64_t triangles = 0;       // Of the meshes, each counted once.
    std::uint64_t drawnTriangles = 0;  // Of the instances: what a frame draws.
    std::size_t materials = 0;         // Including the glTF default material when appended.
    std::size_t textures = 0;
    std::size_t images = 0;
    std::size_t lights = 0;
    std::size_t placedLights = 0;  // Nodes of the scene that place a light.
    std::size_t cameras = 0;
    std::size_t placedCameras = 0;
    std::size_t nodes = 0;
    std::size_t instances = 0;
    // Triangles of the meshes (each counted once) when every primitive draws its level k of
    // detail, or its coarsest level if it has fewer; one entry per level, level 0 first. Empty
    // when no primitive has levels (LoadOptions::buildLevelsOfDetail).
    std::vector<std::uint64_t> levelTriangles;
    std::size_t primitivesWithLevels = 0;
};

// One extension the file uses or requires. "shaded": Encore implements it and draws with it;
// "ignored": the asset is drawn without it. A required one is always implemented (the loader
// refuses the others), so `required` accompanies "shaded".
struct ExtensionInfo {
    std::string name;
    std::string status;  // "shaded" or "ignored".
    bool required = false;
};

struct MaterialNote {
    std::size_t index = 0;
    std::string name;
    std::vector<std::string> ignoredExtensions;
};

// A KTX2 image of KHR_texture_basisu, which Encore cannot decode, and what draws instead.
struct BasisuImageNote {
    std::size_t index = 0;
    std::string name;
    // The textures naming it, each with the image it draws instead (nullopt: a default texture).
    std::vector<std::pair<std::size_t, std::optional<std::size_t>>> textures;
};

struct ModelSummary {
    std::string file;
    ModelCounts counts;
    std::vector<ExtensionInfo> extensions;  // Used ones in the file's order, then required-only.
    std::vector<MaterialNote> materials;    // Only materials with ignored extensions.
    std::vector<std::string> variants;      // KHR_materials_variants, by index.
    std::vector<BasisuImageNote> basisuImages;
    std::vector<std::string> warnings;
};

ModelSummary summarizeModel(const SceneData& scene);

// The summary as lines of "key: value" text, ending with a newline.
std::string formatModelSummary(const ModelSummary& summary);

// The same content as a JSON object (counts as integers, extensions as objects).
nlohmann::json modelSummaryJson(const ModelSummary& summary);

}  // namespace encore::scene
