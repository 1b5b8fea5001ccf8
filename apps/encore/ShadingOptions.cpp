#include "ShadingOptions.h"

#include <cmath>
#include <memory>
#include <string>

#include "batch/OptionNames.h"
#include "batch/OptionValues.h"
#include "encore/image/HdrImage.h"

namespace encore::app {

void addShadingOptions(CLI::App& command, ShadingOptions& options) {
    command.add_option("--environment", options.environment,
                       "Equirectangular Radiance .hdr for image-based lighting (default: a "
                       "built-in neutral studio)");
    command
        .add_option("--environment-intensity", options.environmentIntensity,
                    "Multiplies the environment's radiance")
        ->check(CLI::NonNegativeNumber);
    command.add_option("--environment-rotation", options.environmentRotationDegrees,
                       "Turns the environment about the vertical axis (degrees)");
    command
        .add_option("--tonemap", options.toneMapping,
                    "Tone mapping: neutral (Khronos PBR "
                    "Neutral), aces (Hill) or none")
        ->capture_default_str()
        ->check(CLI::IsMember(batch::namesOf(batch::toneMappingNames())));
    command
        .add_option("--exposure", options.exposure, "Multiplies linear colour before tone mapping")
        ->capture_default_str()
        ->check(CLI::NonNegativeNumber);
    command.add_option("--background", options.background,
                       "env (draw the environment), transparent (alpha 0) or #rrggbb "
                       "(default: a neutral dark grey)");
    command.add_flag("--no-ibl", options.noImageBasedLighting,
                     "Light with the file's punctual lights only");
    command.add_flag("--no-lights", options.noPunctualLights,
                     "Ignore the file's KHR_lights_punctual lights");
    command
        .add_option("--debug-channel", options.debugChannel,
                    "Output one shading input instead of the shaded colour: " +
                        batch::nameList(batch::namesOf(batch::debugChannelNames())))
        ->capture_default_str();
}

Result<void> applyShadingOptions(const ShadingOptions& options, render::RendererOptions& renderer) {
    renderer.toneMapping.toneMapping =
        *batch::valueNamed(batch::toneMappingNames(), options.toneMapping);  // Checked by CLI11.
    renderer.toneMapping.exposure = options.exposure;
    if (!options.background.empty()) {
        ENCORE_TRY(
            batch::parseBackground(options.background, "--background", renderer.toneMapping));
    }
    ENCORE_TRY_ASSIGN(
        renderer.lighting.debugChannel,
        batch::parseNamed(batch::debugChannelNames(), options.debugChannel, "--debug-channel"));
    renderer.lighting.environmentIntensity = options.environmentIntensity;
    renderer.lighting.environmentRotationRadians =
        options.environmentRotationDegrees * float(M_PI) / 180.0f;
    renderer.lighting.imageBasedLighting = !options.noImageBasedLighting;
    renderer.lighting.punctualLights = !options.noPunctualLights;
    if (!options.environment.empty()) {
        ENCORE_TRY_ASSIGN(auto panorama, image::readHdr(options.environment));
        renderer.environmentImage = std::make_shared<image::HdrImage>(std::move(panorama));
    }
    return {};
}

}  // namespace encore::app
