#include "scene/ModelInfo.h"

#include <algorithm>
#include <iterator>

namespace encore::scene {

namespace {

void summarizeLevels(const scene::SceneData& scene, ModelCounts& counts) {
    std::size_t deepest = 0;
    for (const scene::Mesh& mesh : scene.meshes) {
        for (const scene::Primitive& primitive : mesh.primitives) {
            deepest = std::max(deepest, primitive.levels.size());
            counts.primitivesWithLevels += primitive.levels.empty() ? 0 : 1;
        }
    }
    if (deepest == 0) {
        return;
    }
    counts.levelTriangles.assign(deepest + 1, 0);
    for (const scene::Mesh& mesh : scene.meshes) {
        for (const scene::Primitive& primitive : mesh.primitives) {
            for (std::size_t k = 0; k <= deepest; ++k) {
                const std::size_t level = std::min(k, primitive.levels.size());
                counts.levelTriangles[k] +=
                    level == 0
                        ? triangleCount(scene, primitive)
                        : scene.accessors[primitive.levels[level - 1].indices.index()].count / 3;
            }
        }
    }
}

}  // namespace

ModelSummary summarizeModel(const scene::SceneData& scene) {
    ModelSummary summary;
    summary.file = scene.sourcePath.string();

    ModelCounts& counts = summary.counts;
    counts.meshes = scene.meshes.size();
    counts.primitives = scene.primitiveCount();
    std::vector<std::uint64_t> meshTriangles(scene.meshes.size(), 0);
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        for (const scene::Primitive& primitive : scene.meshes[m].primitives) {
            meshTriangles[m] += triangleCount(scene, primitive);
        }
        counts.triangles += meshTriangles[m];
    }
    for (const scene::Instance& instance : scene.instances) {
        counts.drawnTriangles += meshTriangles[instance.mesh.index()];
    }
    summarizeLevels(scene, counts);
    counts.materials = scene.materials.size();
    counts.textures = scene.textures.size();
    counts.images = scene.images.size();
    counts.lights = scene.lights.size();
    counts.placedLights = scene.lightInstances.size();
    counts.cameras = scene.cameras.size();
    counts.placedCameras = scene.cameraInstances.size();
    counts.nodes = scene.nodes.size();
    counts.instances = scene.instances.size();

    auto contains = [](const std::vector<std::string>& list, const std::string& name) {
        return std::find(list.begin(), list.end(), name) != list.end();
    };
    auto addExtension = [&](const std::string& name) {
        const bool listed =
            std::any_of(summary.extensions.begin(), summary.extensions.end(),
                        [&name](const ExtensionInfo& info) { return info.name == name; });
        if (!listed) {
            summary.extensions.push_back(
                {name, contains(scene.extensionsIgnored, name) ? "ignored" : "shaded",
                 contains(scene.extensionsRequired, name)});
        }
    };
    // A file may require an extension it forgets to list as used; show it all the same.
    for (const std::string& name : scene.extensionsUsed) {
        addExtension(name);
    }
    for (const std::string& name : scene.extensionsRequired) {
        addExtension(name);
    }

    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        const scene::Material& material = scene.materials[i];
        if (!material.ignoredExtensions.empty()) {
            summary.materials.push_back({i, material.name, material.ignoredExtensions});
        }
    }
    summary.variants = scene.variants;
    for (std::size_t t = 0; t < scene.textures.size(); ++t) {
        const scene::Texture& texture = scene.textures[t];
        if (!texture.basisuImage) {
            continue;
        }
        const std::size_t image = texture.basisuImage->index();
        auto note = std::find_if(summary.basisuImages.begin(), summary.basisuImages.end(),
                                 [&](const BasisuImageNote& n) { return n.index == image; });
        if (note == summary.basisuImages.end()) {
            summary.basisuImages.push_back(
                {image, image < scene.images.size() ? scene.images[image].name : "", {}});
            note = std::prev(summary.basisuImages.end());
        }
        note->textures.emplace_back(t, texture.image.valid()
                                           ? std::optional<std::size_t>(texture.image.index())
                                           : std::nullopt);
    }
    std::sort(summary.basisuImages.begin(), summary.basisuImages.end(),
              [](const BasisuImageNote& a, const BasisuImageNote& b) { return a.index < b.index; });
    summary.warnings = scene.warnings;
    return summary;
}

std::string formatModelSummary(const ModelSummary& summary) {
    const ModelCounts& counts = summary.counts;
    std::string text = "file: " + summary.file + "\n";
    auto line = [&text](const char* key, std::uint64_t value, std::string extra = {}) {
        text += std::string(key) + ": " + std::to_string(value) + extra + "\n";
    };
    line("meshes", counts.meshes);
    line("primitives", counts.primitives);
    line("triangles", counts.triangles,
         " (" + std::to_string(counts.drawnTriangles) + " drawn by the instances)");
    if (!counts.levelTriangles.empty()) {
        std::string perLevel;
        for (std::uint64_t triangles : counts.levelTriangles) {
            perLevel += (perLevel.empty() ? "" : ", ") + std::to_string(triangles);
        }
        line("levels of detail", counts.levelTriangles.size(),
             " (triangles per level: " + perLevel + "; " +
                 std::to_string(counts.primitivesWithLevels) + " of " +
                 std::to_string(counts.primitives) + " primitives have levels)");
    }
    line("materials", counts.materials);
    line("textures", counts.textures);
    line("images", counts.images);
    line("lights", counts.lights, " (" + std::to_string(counts.placedLights) + " placed)");
    line("cameras", counts.cameras, " (" + std::to_string(counts.placedCameras) + " placed)");
    line("nodes", counts.nodes);
    line("instances", counts.instances);

    text += summary.extensions.empty() ? "extensions: none\n" : "extensions:\n";
    for (const ExtensionInfo& extension : summary.extensions) {
        text += "  " + extension.name + ": " + extension.status +
                (extension.required ? ", required" : "") + "\n";
    }
    if (!summary.materials.empty()) {
        text += "materials with ignored extensions:\n";
        for (const MaterialNote& material : summary.materials) {
            std::string names;
            for (const std::string& name : material.ignoredExtensions) {
                names += (names.empty() ? "" : ", ") + name;
            }
            text += "  material " + std::to_string(material.index) +
                    (material.name.empty() ? "" : " ('" + material.name + "')") + ": " + names +
                    "\n";
        }
    }
    if (!summary.variants.empty()) {
        text += "material variants:\n";
        for (std::size_t v = 0; v < summary.variants.size(); ++v) {
            text += "  " + std::to_string(v) + ": " + summary.variants[v] + "\n";
        }
    }
    if (!summary.basisuImages.empty()) {
        text += "images that need KHR_texture_basisu (KTX2, not decoded: no transcoder):\n";
        for (const BasisuImageNote& image : summary.basisuImages) {
            std::string uses;
            for (const auto& [texture, fallback] : image.textures) {
                uses += (uses.empty() ? "" : "; ") + ("texture " + std::to_string(texture)) +
                        (fallback ? " draws image " + std::to_string(*fallback) + " instead"
                                  : " has no fallback (a default texture is drawn)");
            }
            text += "  image " + std::to_string(image.index) +
                    (image.name.empty() ? "" : " ('" + image.name + "')") + ": " + uses + "\n";
        }
    }
    text += summary.warnings.empty() ? "warnings: none\n" : "warnings:\n";
    for (const std::string& warning : summary.warnings) {
        text += "  " + warning + "\n";
    }
    return text;
}

nlohmann::json modelSummaryJson(const ModelSummary& summary) {
    const ModelCounts& counts = summary.counts;
    nlohmann::json json;
    json["file"] = summary.file;
    json["counts"] = {
        {"meshes", counts.meshes},
        {"primitives", counts.primitives},
        {"triangles", counts.triangles},
        {"drawnTriangles", counts.drawnTriangles},
        {"materials", counts.materials},
        {"textures", counts.textures},
        {"images", counts.images},
        {"lights", counts.lights},
        {"placedLights", counts.placedLights},
        {"cameras", counts.cameras},
        {"placedCameras", counts.placedCameras},
        {"nodes", counts.nodes},
        {"instances", counts.instances},
        {"levelTriangles", counts.levelTriangles},
        {"primitivesWithLevels", counts.primitivesWithLevels},
    };
    json["extensions"] = nlohmann::json::array();
    for (const ExtensionInfo& extension : summary.extensions) {
        json["extensions"].push_back({{"name", extension.name},
                                      {"status", extension.status},
                                      {"required", extension.required}});
    }
    json["materialsWithIgnoredExtensions"] = nlohmann::json::array();
    for (const MaterialNote& material : summary.materials) {
        json["materialsWithIgnoredExtensions"].push_back(
            {{"index", material.index},
             {"name", material.name},
             {"ignoredExtensions", material.ignoredExtensions}});
    }
    json["variants"] = summary.variants;
    json["basisuImages"] = nlohmann::json::array();
    for (const BasisuImageNote& image : summary.basisuImages) {
        nlohmann::json textures = nlohmann::json::array();
        for (const auto& [texture, fallback] : image.textures) {
            textures.push_back({{"texture", texture},
                                {"fallbackImage",
                                 fallback ? nlohmann::json(*fallback) : nlohmann::json(nullptr)}});
        }
        json["basisuImages"].push_back(
            {{"image", image.index}, {"name", image.name}, {"textures", textures}});
    }
    json["warnings"] = summary.warnings;
    return json;
}

}  // namespace encore::scene
