#pragma once

// Command-line options for how a picture is lit and mapped, shared by the commands that render
// (render, stats, bench): environment, tone mapping, exposure, background, lights.

#include <CLI/CLI.hpp>

#include <string>

#include "encore/core/Result.h"
#include "encore/render/Renderer.h"

namespace encore::app {

struct ShadingOptions {
    std::string environment;  // An equirectangular .hdr; empty: the built-in studio.
    float environmentIntensity = 1.0f;
    float environmentRotationDegrees = 0.0f;
    std::string toneMapping = "neutral";
    float exposure = 1.0f;
    std::string background;  // env | transparent | #rrggbb; empty: the neutral default.
    bool noImageBasedLighting = false;
    bool noPunctualLights = false;
    std::string debugChannel = "none";
};

// (`encore batch` takes these from the batch's description of its options, with ranges.)
void addShadingOptions(CLI::App& command, ShadingOptions& options);

// Fills the lighting, tone mapping and environment of `renderer` options; loads the
// environment file (errors name it).
Result<void> applyShadingOptions(const ShadingOptions& options, render::RendererOptions& renderer);

}  // namespace encore::app
