#include "batch/ModelMetadata.h"

#include "core/FileIO.h"
#include "core/Sha256.h"

namespace encore::batch {
namespace {

namespace fs = std::filesystem;

// The reason in the loader's warning about image `index` ("<file>: image 3 ('a.png') cannot be
// read (<reason>); drawing it with a default texture."), or a general one.
std::string imageProblem(const scene::SceneData& scene, std::size_t index) {
    const std::string subject = ": image " + std::to_string(index) + " (";
    const std::string opening = "cannot be read (";
    const std::string closing = "); drawing it with a default texture.";
    for (const std::string& warning : scene.warnings) {
        const std::size_t at = warning.find(subject);
        const std::size_t start = warning.find(opening, at == std::string::npos ? 0 : at);
        if (at == std::string::npos || start == std::string::npos || !warning.ends_with(closing)) {
            continue;
        }
        const std::size_t from = start + opening.size();
        return warning.substr(from, warning.size() - closing.size() - from);
    }
    return "It could not be read.";
}

nlohmann::json vectorJson(const glm::vec3& value) {
    return {value.x, value.y, value.z};
}

}  // namespace

Result<scene::SceneData> loadModelFile(const fs::path& path,
                                       const scene::LoadOptions& options,
                                       ModelFacts& facts) {
    // scene::loadScene's steps, with the bytes hashed between reading and parsing.
    auto bytes = readFile(path);
    if (!bytes) {
        return bytes.error().withContext(path.string());
    }
    facts.fileBytes = bytes->size();
    facts.sha256 = Sha256::hex(*bytes);
    auto scene = scene::loadSceneFromMemory(*bytes, path.parent_path(), path.string(), options);
    if (scene) {
        scene->sourcePath = path;
        describeModel(*scene, facts);
    }
    return scene;
}

void describeModel(const scene::SceneData& scene, ModelFacts& facts) {
    facts.triangles = scene.drawnTriangleCount();
    facts.vertices = 0;
    for (const scene::Instance& instance : scene.instances) {
        for (const scene::Primitive& primitive : scene.meshes[instance.mesh.index()].primitives) {
            facts.vertices += primitive.vertexCount;
        }
    }
    facts.meshes = scene.meshes.size();
    facts.primitives = scene.primitiveCount();
    facts.instances = scene.instances.size();
    facts.nodes = scene.nodes.size();
    facts.materials = 0;
    for (const scene::Material& material : scene.materials) {
        facts.materials += material.isDefault ? 0 : 1;
    }
    facts.textures = scene.textures.size();
    facts.images = scene.images.size();
    facts.lights = scene.lights.size();
    facts.cameras = scene.cameras.size();
    facts.skins = scene.skins.size();
    facts.imagesFailed.clear();
    for (std::size_t index = 0; index < scene.images.size(); ++index) {
        if (scene.images[index].rgba8.empty()) {
            facts.imagesFailed.push_back(
                {index, scene.images[index].name, imageProblem(scene, index)});
        }
    }
    facts.imagesDownscaled.clear();
    for (std::size_t index = 0; index < scene.images.size(); ++index) {
        const scene::Image& image = scene.images[index];
        if (image.downscaled()) {
            facts.imagesDownscaled.push_back({index, image.name, image.sourceWidth,
                                              image.sourceHeight, image.width, image.height});
        }
    }
    facts.extensionsUsed = scene.extensionsUsed;
    facts.extensionsRequired = scene.extensionsRequired;
    facts.extensionsIgnored = scene.extensionsIgnored;
    facts.warnings = scene.warnings;
    facts.bounds = scene.bounds;
    facts.animations.clear();
    for (const scene::Animation& animation : scene.animations) {
        facts.animations.push_back({animation.name, animation.end, animation.channels.size()});
    }
}

std::uint64_t coveredPixels(std::span<const std::uint8_t> pixels) {
    std::uint64_t covered = 0;
    for (std::size_t alpha = 3; alpha < pixels.size(); alpha += 4) {
        covered += pixels[alpha] != 0 ? 1 : 0;
    }
    return covered;
}

std::vector<std::uint32_t> blankViews(std::span<const std::uint64_t> coveredPixels,
                                      std::uint32_t threshold) {
    std::vector<std::uint32_t> blank;
    for (std::size_t view = 0; view < coveredPixels.size(); ++view) {
        if (coveredPixels[view] < threshold) {
            blank.push_back(std::uint32_t(view));
        }
    }
    return blank;
}

nlohmann::json metadataJson(const BatchInput& input,
                            const ModelFacts& facts,
                            const ModelTimes& times,
                            std::uint32_t views,
                            std::span<const std::uint64_t> coveredPixels,
                            std::uint32_t blankThreshold,
                            const ModelDrawing& drawing,
                            const nlohmann::json& camera) {
    nlohmann::json failed = nlohmann::json::array();
    for (const ModelFacts::FailedImage& image : facts.imagesFailed) {
        failed.push_back({{"index", image.index}, {"name", image.name}, {"error", image.error}});
    }
    nlohmann::json downscaled = nlohmann::json::array();
    for (const ModelFacts::DownscaledImage& image : facts.imagesDownscaled) {
        downscaled.push_back({{"index", image.index},
                              {"name", image.name},
                              {"originalWidth", image.originalWidth},
                              {"originalHeight", image.originalHeight},
                              {"width", image.width},
                              {"height", image.height}});
    }
    nlohmann::json animations = nlohmann::json::array();
    for (const ModelFacts::AnimationFacts& animation : facts.animations) {
        animations.push_back({{"name", animation.name},
                              {"seconds", animation.seconds},
                              {"channels", animation.channels}});
    }
    nlohmann::json json;
    json["file"] = input.path.string();
    json["name"] = input.name;
    json["fileBytes"] = facts.fileBytes;
    json["sha256"] = facts.sha256;
    json["triangles"] = facts.triangles;
    json["vertices"] = facts.vertices;
    json["meshes"] = facts.meshes;
    json["primitives"] = facts.primitives;
    json["instances"] = facts.instances;
    json["nodes"] = facts.nodes;
    json["materials"] = facts.materials;
    json["textures"] = facts.textures;
    json["images"] = facts.images;
    json["imagesFailed"] = std::move(failed);
    json["imagesDownscaled"] = std::move(downscaled);
    json["lights"] = facts.lights;
    json["cameras"] = facts.cameras;
    json["skins"] = facts.skins;
    json["animations"] = std::move(animations);
    json["extensionsUsed"] = facts.extensionsUsed;
    json["extensionsRequired"] = facts.extensionsRequired;
    json["extensionsIgnored"] = facts.extensionsIgnored;
    json["warnings"] = facts.warnings;
    json["bounds"] = facts.bounds.empty() ? nlohmann::json(nullptr)
                                          : nlohmann::json{{"min", vectorJson(facts.bounds.min)},
                                                           {"max", vectorJson(facts.bounds.max)}};
    json["views"] = views;
    json["blankThreshold"] = blankThreshold;
    if (coveredPixels.empty()) {
        json["coveredPixels"] = nullptr;
        json["blankViews"] = nullptr;
    } else {
        json["coveredPixels"] = coveredPixels;
        json["blankViews"] = blankViews(coveredPixels, blankThreshold);
    }
    json["seconds"] = {{"load", times.load},
                       {"upload", times.upload},
                       {"render", times.render},
                       {"encode", times.encode}};
    json["strategy"] = drawing.strategy;
    json["gpu"] = {{"objectsCreated", drawing.objectsCreated},
                   {"bytesMapped", drawing.bytesMapped}};
    if (!camera.is_null()) {
        json["camera"] = camera;
    }
    return json;
}

}  // namespace encore::batch
