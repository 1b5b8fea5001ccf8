#pragma once

// How linear scene colour becomes display colour: exposure, a tone-mapping operator and what is
// behind the scene (tone_map.wgsl). Applied either by the scene shaders as they shade or by the
// tone-mapping pass of an HDR target (ToneMapper); both read these values from uniforms.

#include <glm/glm.hpp>

#include <cstdint>

namespace encore::render {

enum class ToneMapping : std::uint32_t {
    None,        // Linear, clamped at 1.
    PbrNeutral,  // Khronos PBR Neutral (the default, as the Khronos Sample Renderer).
    AcesHill,    // ACES filmic, Stephen Hill's fit.
};

enum class BackgroundKind : std::uint32_t {
    Color,        // An opaque colour behind the scene.
    Transparent,  // Alpha 0 where nothing is drawn; colours are straight (not premultiplied).
    Environment,  // The environment map, drawn by EnvironmentBackground and tone mapped.
};

struct ToneMappingOptions {
    ToneMapping toneMapping = ToneMapping::PbrNeutral;
    float exposure = 1.0f;  // Multiplies linear colour before tone mapping.
    BackgroundKind background = BackgroundKind::Color;
    // Linear RGB of BackgroundKind::Color; the default is a neutral dark grey.
    glm::vec3 backgroundColor{0.05f, 0.05f, 0.06f};

    bool operator==(const ToneMappingOptions&) const = default;
};

}  // namespace encore::render
