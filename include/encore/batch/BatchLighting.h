#pragma once

// How each model of a batch is lit: one environment of a folder of HDR panoramas, turned and
// scaled by amounts drawn for the model, and what transforms.json records of it. The draws come
// from the batch's seed and the model's name (ModelSeed.h), so a resumed or re-ordered run
// lights every model as the first run did.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "encore/batch/ViewRig.h"
#include "encore/core/Result.h"
#include "encore/render/RendererOptions.h"

namespace encore::batch {

// The name transforms.json gives the built-in studio environment.
inline constexpr const char* kStudioEnvironmentName = "studio";

struct LightingVariation {
    // A folder of equirectangular Radiance .hdr files (not searched recursively): each model is
    // lit by one of them, drawn for it. Empty: every model by the renderer options' environment.
    std::filesystem::path environmentDirectory;
    // Degrees about +Y (counter-clockwise seen from above), drawn for each model from the range
    // ([0, 360) for `--environment-rotation random`). Unset: RendererOptions::lighting's.
    std::optional<ValueRange> rotationDegrees;
    // What the environment's radiance is multiplied by, drawn for each model. Unset:
    // RendererOptions::lighting's.
    std::optional<ValueRange> intensity;
    // What frames record as the environment when no folder is given: the file named by
    // `--environment`, or kStudioEnvironmentName when empty.
    std::string environmentName;
};

// The lighting of one model.
struct ModelLighting {
    std::filesystem::path environmentFile;  // Empty: the renderer options' environment.
    // As transforms.json records it: the file's path relative to the folder, or
    // LightingVariation::environmentName.
    std::string environment;
    float rotationDegrees = 0.0f;  // As recorded.
    float rotationRadians = 0.0f;  // As rendered (LightingParameters::environmentRotationRadians).
    float intensity = 1.0f;

    bool operator==(const ModelLighting&) const = default;
};

// The .hdr files of `directory` (any letter case), sorted by name. Fails with InvalidArgument
// when it is not a folder or holds none.
Result<std::vector<std::filesystem::path>> environmentFiles(const std::filesystem::path& directory);

// Which of `count` environment files the model named `modelName` is lit by (modelLighting's
// choice), in 0..count-1; 0 when count is 0.
std::size_t environmentIndex(std::size_t count, std::uint64_t seed, std::string_view modelName);

// The lighting of the model named `modelName`: one of `environments` (environmentFiles of the
// variation's folder; ignored without one), the rotation and intensity drawn from the variation's
// ranges, or `base`'s where it has none.
ModelLighting modelLighting(const LightingVariation& variation,
                            std::span<const std::filesystem::path> environments,
                            const render::LightingParameters& base,
                            std::uint64_t seed,
                            std::string_view modelName);

}  // namespace encore::batch
