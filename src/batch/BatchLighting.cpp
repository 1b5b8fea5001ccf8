#include "encore/batch/BatchLighting.h"

#include <algorithm>
#include <cmath>

#include "batch/ModelSeed.h"

namespace encore::batch {

namespace fs = std::filesystem;

Result<std::vector<fs::path>> environmentFiles(const fs::path& directory) {
    std::error_code ec;
    if (!fs::is_directory(directory, ec)) {
        return makeError(ErrorCode::InvalidArgument,
                         "The environment folder '" + directory.string() + "' is not a folder.");
    }
    std::vector<fs::path> files;
    for (auto it = fs::directory_iterator(directory, ec); !ec && it != fs::directory_iterator();
         it.increment(ec)) {
        std::string extension = it->path().extension().string();
        std::transform(extension.begin(), extension.end(), extension.begin(),
                       [](unsigned char c) { return char(std::tolower(c)); });
        if (extension == ".hdr" && it->is_regular_file(ec)) {
            files.push_back(it->path());
        }
    }
    if (ec) {
        return makeError(ErrorCode::InvalidArgument, "Cannot list the environment folder '" +
                                                         directory.string() + "' (" + ec.message() +
                                                         ").");
    }
    if (files.empty()) {
        return makeError(
            ErrorCode::InvalidArgument,
            "The environment folder '" + directory.string() + "' holds no Radiance .hdr file.");
    }
    std::sort(files.begin(), files.end());
    return files;
}

std::size_t environmentIndex(std::size_t count, std::uint64_t seed, std::string_view modelName) {
    if (count == 0) {
        return 0;
    }
    std::mt19937_64 draws = randomStream(modelSeed(seed, modelName), RandomStream::Lighting);
    return std::min(count - 1, std::size_t(unitInterval(draws) * double(count)));
}

ModelLighting modelLighting(const LightingVariation& variation,
                            std::span<const fs::path> environments,
                            const render::LightingParameters& base,
                            std::uint64_t seed,
                            std::string_view modelName) {
    std::mt19937_64 draws = randomStream(modelSeed(seed, modelName), RandomStream::Lighting);
    // Always three draws, in this order, so that one choice never shifts another; the first is
    // environmentIndex's.
    (void)unitInterval(draws);
    const double rotationDraw = unitInterval(draws);
    const double intensityDraw = unitInterval(draws);

    ModelLighting lighting;
    if (!variation.environmentDirectory.empty() && !environments.empty()) {
        const std::size_t index = environmentIndex(environments.size(), seed, modelName);
        lighting.environmentFile = environments[index];
        lighting.environment =
            environments[index].lexically_relative(variation.environmentDirectory).generic_string();
    } else {
        lighting.environment =
            variation.environmentName.empty() ? kStudioEnvironmentName : variation.environmentName;
    }
    if (variation.rotationDegrees) {
        lighting.rotationDegrees = variation.rotationDegrees->at(rotationDraw);
        // As `encore render --environment-rotation` converts it.
        lighting.rotationRadians = lighting.rotationDegrees * float(M_PI) / 180.0f;
    } else {
        lighting.rotationRadians = base.environmentRotationRadians;
        lighting.rotationDegrees = float(double(base.environmentRotationRadians) * 180.0 / M_PI);
    }
    lighting.intensity =
        variation.intensity ? variation.intensity->at(intensityDraw) : base.environmentIntensity;
    return lighting;
}

}  // namespace encore::batch
