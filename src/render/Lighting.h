#pragma once

// SceneLighting owns what group 0 binds besides the camera: the lighting uniform (environment
// rotation and intensity, light count, debug channel, the display transform), the punctual lights
// of the scene (KHR_lights_punctual, one storage buffer) and the image-based-lighting Environment.
// All of it changes through buffers and in-place texture writes: a recorded render bundle stays
// valid when the environment, its intensity or rotation, or a light changes. Only a scene with more
// lights than the buffer holds grows the buffer, which replaces the frame bind group (the
// renderer prepares strategies again then anyway).

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "encore/core/Result.h"
#include "encore/render/RendererOptions.h"
#include "encore/scene/SceneData.h"
#include "render/Environment.h"

namespace encore::render {

// struct Lighting of scene_lighting.wgsl, byte for byte.
struct LightingUniform {
    float environmentRotation[12];  // mat3x3f: three columns of vec3 padded to 16 bytes.
    float environmentIntensity;
    float specularLevels;
    std::uint32_t lightCount;
    std::uint32_t imageBasedLighting;
    std::uint32_t debugChannel;
    float exposure;
    std::uint32_t toneMapping;    // ToneMapping.
    std::uint32_t displayMapped;  // 1: scene shaders write display colour (no HDR pass).
    EnvironmentAtlasUniform atlas;
};
static_assert(sizeof(LightingUniform) == 256);

// struct PunctualLight of scene_lighting.wgsl, byte for byte.
struct LightUniform {
    float position[3];
    float range;
    float direction[3];
    std::uint32_t kind;  // 0 directional, 1 point, 2 spot.
    float color[3];
    float intensity;
    float innerConeCos;
    float outerConeCos;
    float padding[2];
};
static_assert(sizeof(LightUniform) == 64);

LightUniform makeLightUniform(const scene::Light& light, const scene::LightInstance& placed);

class SceneLighting {
  public:
    // Uses `environment` (shared: several renderers may light with one).
    static Result<SceneLighting> create(const wgpu::Device& device,
                                        const wgpu::Queue& queue,
                                        std::shared_ptr<Environment> environment);

    SceneLighting(SceneLighting&&) noexcept = default;
    SceneLighting& operator=(SceneLighting&&) noexcept = default;

    void setParameters(const LightingParameters& parameters);
    const LightingParameters& parameters() const { return mParameters; }

    // The display transform the scene shaders apply (`inShaders`: the target has no HDR pass),
    // or none (linear output for an HDR target's tone-mapping pass).
    void setDisplayMapping(const ToneMappingOptions& options, bool inShaders);

    // Uploads the placed lights of `scene`. Returns true when the light buffer had to grow, so
    // bind groups that reference it must be created again.
    bool setSceneLights(const scene::SceneData& scene);
    // Rewrites one placed light (an index into SceneData::lightInstances) in place.
    Result<void> updateLight(std::size_t lightInstance,
                             const scene::Light& light,
                             const scene::LightInstance& placed);
    std::size_t lightCount() const { return mLightCount; }

    // Replaces the environment's contents (the same textures: bind groups stay valid).
    Result<void> loadEnvironment(const image::HdrImage& panorama);
    // Lights with another environment: bind groups that bound the previous one must be made
    // again (FrameUniforms::bindLighting).
    void setEnvironment(std::shared_ptr<Environment> environment);
    Environment& environment() { return *mEnvironment; }
    const Environment& environment() const { return *mEnvironment; }
    // For another renderer to light with the same environment (RendererOptions::environment).
    const std::shared_ptr<Environment>& sharedEnvironment() const { return mEnvironment; }

    const wgpu::Buffer& uniformBuffer() const { return mUniform; }
    const wgpu::Buffer& lightBuffer() const { return mLights; }

  private:
    SceneLighting() = default;
    void writeUniform();

    wgpu::Device mDevice;
    wgpu::Queue mQueue;
    std::shared_ptr<Environment> mEnvironment;
    wgpu::Buffer mUniform;
    wgpu::Buffer mLights;
    std::size_t mLightCapacity = 0;
    std::size_t mLightCount = 0;
    LightingParameters mParameters;
    ToneMappingOptions mDisplay;
    bool mDisplayInShaders = false;
};

}  // namespace encore::render
