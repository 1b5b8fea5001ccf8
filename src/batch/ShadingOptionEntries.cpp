// The options that light and tone-map a batch's views: environment, its rotation and intensity,
// punctual lights, exposure, tone mapping and background.

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "batch/OptionEntries.h"
#include "batch/OptionNames.h"
#include "batch/OptionValues.h"
#include "encore/batch/BatchLighting.h"
#include "encore/image/HdrImage.h"

namespace encore::batch::optiontable {

// Lighting, tone mapping and background.
void addShadingOptions(std::vector<Entry>& entries) {
    entries.push_back(
        text("environment", OptionForm::Text, "FILE",
             "Equirectangular Radiance .hdr for image-based lighting (default: a "
             "built-in neutral studio)",
             [](BatchOptions& o, std::string_view value, std::string_view) -> Result<void> {
                 ENCORE_TRY_ASSIGN(auto panorama, image::readHdr(std::string(value)));
                 o.renderer.environmentImage =
                     std::make_shared<image::HdrImage>(std::move(panorama));
                 o.lighting.environmentName = std::string(value);
                 return Result<void>{};
             })
            .excluding({"environment-dir"}));
    entries.push_back(
        text("environment-dir", OptionForm::Text, "DIR",
             "Light each model with one Radiance .hdr of this folder, drawn from "
             "--seed and the model's name",
             [](BatchOptions& o, std::string_view value, std::string_view) -> Result<void> {
                 ENCORE_TRY(environmentFiles(std::string(value)));
                 o.lighting.environmentDirectory = std::string(value);
                 return Result<void>{};
             })
            .excluding({"environment"}));
    entries.push_back(
        text("environment-rotation", OptionForm::Range, "DEG|MIN:MAX|random",
             "Turns the environment about the vertical axis: degrees, MIN:MAX or "
             "random (0:360), drawn per model",
             [](BatchOptions& o, std::string_view value, std::string_view shown) -> Result<void> {
                 if (value == "random") {
                     o.lighting.rotationDegrees = ValueRange(0.0f, 360.0f);
                     return Result<void>{};
                 }
                 ENCORE_TRY_ASSIGN(o.lighting.rotationDegrees, parseRange(value, shown));
                 return Result<void>{};
             }));
    entries.push_back(range("environment-intensity", "X|MIN:MAX", "",
                            "Multiplies the environment's radiance: a number or MIN:MAX, drawn "
                            "per model",
                            [](BatchOptions& o, ValueRange r) { o.lighting.intensity = r; }));
    entries.push_back(
        named<render::ToneMapping>(
            "tonemap", "neutral",
            "Tone mapping: neutral (Khronos PBR Neutral), aces (Hill) or none", toneMappingNames(),
            [](BatchOptions& o, render::ToneMapping t) { o.renderer.toneMapping.toneMapping = t; })
            .keyword("tone_mapping"));
    entries.push_back(
        number("exposure", "X", "1", "Multiplies linear colour before tone mapping", 0.0f, kNoLimit,
               [](BatchOptions& o, float v) { o.renderer.toneMapping.exposure = v; }));
    entries.push_back(
        text("background", OptionForm::Text, "env|transparent|#rrggbb",
             "env (draw the environment), transparent (alpha 0) or #rrggbb",
             [](BatchOptions& o, std::string_view value, std::string_view shown) -> Result<void> {
                 return parseBackground(value, shown, o.renderer.toneMapping);
             }));
    entries.back().description.defaultValue = "transparent";
    entries.push_back(
        flag("no-ibl", "Light with the file's punctual lights only", [](BatchOptions& o, bool on) {
            o.renderer.lighting.imageBasedLighting = !on;
        }).keyword("image_based_lighting", /*negated=*/true));
    entries.push_back(
        flag("no-lights", "Ignore the file's KHR_lights_punctual lights",
             [](BatchOptions& o, bool on) { o.renderer.lighting.punctualLights = !on; })
            .keyword("punctual_lights", /*negated=*/true));
    entries.push_back(named<render::DebugChannel>(
        "debug-channel", "none",
        "Output one shading input instead of the shaded colour: " +
            nameList(namesOf(debugChannelNames())),
        debugChannelNames(),
        [](BatchOptions& o, render::DebugChannel c) { o.renderer.lighting.debugChannel = c; }));
}

}  // namespace encore::batch::optiontable
