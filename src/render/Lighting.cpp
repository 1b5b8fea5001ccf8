#include "render/Lighting.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "gpu/Upload.h"

namespace encore::render {

namespace {
constexpr wgpu::BufferUsage kLightUsage = wgpu::BufferUsage::Storage | wgpu::BufferUsage::CopyDst;
}

LightUniform makeLightUniform(const scene::Light& light, const scene::LightInstance& placed) {
    LightUniform uniform{};
    for (int i = 0; i < 3; ++i) {
        uniform.position[i] = placed.position[i];
        uniform.direction[i] = placed.direction[i];
        uniform.color[i] = light.color[i];
    }
    uniform.range = light.range;
    uniform.intensity = light.intensity;
    switch (light.type) {
        case scene::LightType::Directional:
            uniform.kind = 0;
            break;
        case scene::LightType::Point:
            uniform.kind = 1;
            break;
        case scene::LightType::Spot:
            uniform.kind = 2;
            break;
    }
    uniform.innerConeCos = std::cos(light.innerConeAngle);
    uniform.outerConeCos = std::cos(light.outerConeAngle);
    if (uniform.innerConeCos - uniform.outerConeCos < 1e-4f) {
        // smoothstep needs an edge width; equal cones are a hard edge.
        uniform.innerConeCos = uniform.outerConeCos + 1e-4f;
    }
    return uniform;
}

Result<SceneLighting> SceneLighting::create(const wgpu::Device& device,
                                            const wgpu::Queue& queue,
                                            std::shared_ptr<Environment> environment) {
    if (!environment) {
        return makeError(ErrorCode::InvalidArgument, "Scene lighting needs an environment.");
    }
    SceneLighting lighting;
    lighting.mDevice = device;
    lighting.mQueue = queue;
    lighting.mEnvironment = std::move(environment);
    lighting.mUniform =
        gpu::createBuffer(device, wgpu::BufferUsage::Uniform | wgpu::BufferUsage::CopyDst,
                          sizeof(LightingUniform), "lighting uniform");
    lighting.mLightCapacity = 1;  // A binding needs one element even when there are no lights.
    lighting.mLights =
        gpu::createBuffer(device, kLightUsage, sizeof(LightUniform), "punctual lights");
    const LightUniform none{};
    queue.WriteBuffer(lighting.mLights, 0, &none, sizeof(none));
    lighting.writeUniform();
    return lighting;
}

void SceneLighting::writeUniform() {
    LightingUniform uniform{};
    // Rotating the environment by +angle about +Y means looking it up with the inverse rotation.
    const float c = std::cos(mParameters.environmentRotationRadians);
    const float s = std::sin(mParameters.environmentRotationRadians);
    const float columns[3][3] = {{c, 0.0f, s}, {0.0f, 1.0f, 0.0f}, {-s, 0.0f, c}};
    for (int column = 0; column < 3; ++column) {
        for (int row = 0; row < 3; ++row) {
            uniform.environmentRotation[column * 4 + row] = columns[column][row];
        }
    }
    uniform.environmentIntensity = mParameters.environmentIntensity;
    uniform.specularLevels = float(mEnvironment->specularLevels());
    uniform.lightCount = mParameters.punctualLights ? std::uint32_t(mLightCount) : 0u;
    uniform.imageBasedLighting = mParameters.imageBasedLighting ? 1u : 0u;
    uniform.debugChannel = static_cast<std::uint32_t>(mParameters.debugChannel);
    uniform.exposure = mDisplay.exposure;
    uniform.toneMapping = static_cast<std::uint32_t>(mDisplay.toneMapping);
    uniform.displayMapped = mDisplayInShaders ? 1u : 0u;
    uniform.atlas = makeEnvironmentAtlasUniform(mEnvironment->atlasLayout());
    mQueue.WriteBuffer(mUniform, 0, &uniform, sizeof(uniform));
}

void SceneLighting::setParameters(const LightingParameters& parameters) {
    mParameters = parameters;
    writeUniform();
}

void SceneLighting::setDisplayMapping(const ToneMappingOptions& options, bool inShaders) {
    mDisplay = options;
    mDisplayInShaders = inShaders;
    writeUniform();
}

bool SceneLighting::setSceneLights(const scene::SceneData& scene) {
    std::vector<LightUniform> uniforms;
    uniforms.reserve(scene.lightInstances.size());
    for (const scene::LightInstance& placed : scene.lightInstances) {
        if (placed.light.index() < scene.lights.size()) {
            uniforms.push_back(makeLightUniform(scene.lights[placed.light.index()], placed));
        }
    }
    bool grew = false;
    if (uniforms.size() > mLightCapacity) {
        mLightCapacity = uniforms.size();
        mLights = gpu::createBuffer(mDevice, kLightUsage, mLightCapacity * sizeof(LightUniform),
                                    "punctual lights");
        grew = true;
    }
    if (!uniforms.empty()) {
        mQueue.WriteBuffer(mLights, 0, uniforms.data(), uniforms.size() * sizeof(LightUniform));
    }
    mLightCount = uniforms.size();
    writeUniform();
    return grew;
}

Result<void> SceneLighting::updateLight(std::size_t lightInstance,
                                        const scene::Light& light,
                                        const scene::LightInstance& placed) {
    if (lightInstance >= mLightCount) {
        return makeError(ErrorCode::InvalidArgument, "Light " + std::to_string(lightInstance) +
                                                         " does not exist (the scene has " +
                                                         std::to_string(mLightCount) +
                                                         " placed lights).");
    }
    const LightUniform uniform = makeLightUniform(light, placed);
    mQueue.WriteBuffer(mLights, lightInstance * sizeof(LightUniform), &uniform, sizeof(uniform));
    return {};
}

void SceneLighting::setEnvironment(std::shared_ptr<Environment> environment) {
    mEnvironment = std::move(environment);
    writeUniform();  // Its atlas layout and level count.
}

Result<void> SceneLighting::loadEnvironment(const image::HdrImage& panorama) {
    ENCORE_TRY(mEnvironment->load(panorama));
    writeUniform();  // The level count is fixed, but keep the uniform in step regardless.
    return {};
}

}  // namespace encore::render
