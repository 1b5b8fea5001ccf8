#include "ShadingOptions.h"

#include <cmath>
#include <map>
#include <memory>
#include <string>

#include "encore/image/HdrImage.h"
#include "image/Srgb.h"

namespace encore::app {

namespace {

const std::map<std::string, render::ToneMapping>& toneMappings() {
    static const std::map<std::string, render::ToneMapping> names = {
        {"neutral", render::ToneMapping::PbrNeutral},
        {"aces", render::ToneMapping::AcesHill},
        {"none", render::ToneMapping::None}};
    return names;
}

const std::map<std::string, render::DebugChannel>& debugChannels() {
    static const std::map<std::string, render::DebugChannel> names = {
        {"none", render::DebugChannel::Shaded},
        {"base-color", render::DebugChannel::BaseColor},
        {"normal", render::DebugChannel::Normal},
        {"metallic", render::DebugChannel::Metallic},
        {"roughness", render::DebugChannel::Roughness},
        {"occlusion", render::DebugChannel::Occlusion},
        {"emissive", render::DebugChannel::Emissive},
        {"depth", render::DebugChannel::Depth},
        {"material", render::DebugChannel::Material},
        {"segment-node", render::DebugChannel::SegmentNode},
        {"segment-mesh", render::DebugChannel::SegmentMesh},
        {"segment-material", render::DebugChannel::SegmentMaterial}};
    return names;
}

std::string names(const auto& table) {
    std::string list;
    for (const auto& [name, value] : table) {
        list += (list.empty() ? "" : ", ") + name;
    }
    return list;
}

Result<glm::vec3> parseHexColor(const std::string& text) {
    const auto invalid = [&] {
        return makeError(
            ErrorCode::InvalidArgument,
            "The background '" + text + "' is not env, transparent or a colour written #rrggbb.");
    };
    if (text.size() != 7 || text[0] != '#') {
        return invalid();
    }
    glm::vec3 color;
    for (int channel = 0; channel < 3; ++channel) {
        const std::string digits = text.substr(1 + 2 * channel, 2);
        if (digits.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos) {
            return invalid();
        }
        color[channel] = float(image::srgbToLinear(std::stoi(digits, nullptr, 16) / 255.0));
    }
    return color;
}

}  // namespace

void addShadingOptions(CLI::App& command, ShadingOptions& options, bool environmentLevels) {
    command.add_option("--environment", options.environment,
                       "Equirectangular Radiance .hdr for image-based lighting (default: a "
                       "built-in neutral studio)");
    if (environmentLevels) {
        command
            .add_option("--environment-intensity", options.environmentIntensity,
                        "Multiplies the environment's radiance")
            ->check(CLI::NonNegativeNumber);
        command.add_option("--environment-rotation", options.environmentRotationDegrees,
                           "Turns the environment about the vertical axis (degrees)");
    }
    command
        .add_option("--tonemap", options.toneMapping,
                    "Tone mapping: neutral (Khronos PBR "
                    "Neutral), aces (Hill) or none")
        ->capture_default_str()
        ->check(CLI::IsMember({"neutral", "aces", "none"}));
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
        .add_option(
            "--debug-channel", options.debugChannel,
            "Output one shading input instead of the shaded colour: " + names(debugChannels()))
        ->capture_default_str();
}

Result<void> applyShadingOptions(const ShadingOptions& options, render::RendererOptions& renderer) {
    renderer.toneMapping.toneMapping = toneMappings().at(options.toneMapping);
    renderer.toneMapping.exposure = options.exposure;
    if (options.background == "env") {
        renderer.toneMapping.background = render::BackgroundKind::Environment;
    } else if (options.background == "transparent") {
        renderer.toneMapping.background = render::BackgroundKind::Transparent;
    } else if (!options.background.empty()) {
        ENCORE_TRY_ASSIGN(auto color, parseHexColor(options.background));
        renderer.toneMapping.background = render::BackgroundKind::Color;
        renderer.toneMapping.backgroundColor = color;
    }
    const auto channel = debugChannels().find(options.debugChannel);
    if (channel == debugChannels().end()) {
        return makeError(ErrorCode::InvalidArgument,
                         "Unknown debug channel '" + options.debugChannel +
                             "' (known: " + names(debugChannels()) + ").");
    }
    renderer.lighting.debugChannel = channel->second;
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
