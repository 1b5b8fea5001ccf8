// What the environment tests share: small maps, probes that sample the cube maps and the atlas
// on the GPU, panoramas with known directions.

#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include "GpuTestSupport.h"
#include "encore/image/HdrImage.h"
#include "gpu/Readback.h"
#include "render/Environment.h"
#include "render/Lighting.h"
#include "shaders/EmbeddedFiles.h"
#include "shaders/ShaderComposer.h"

namespace encore::render::environment_test {

using Vec3 = std::array<float, 3>;
constexpr float kPi = std::numbers::pi_v<float>;

// Small maps: every property tested here holds at any size, and lavapipe is a CPU.
inline EnvironmentOptions smallOptions() {
    EnvironmentOptions options;
    options.specularSize = 64;
    options.specularLevels = 5;
    options.irradianceSize = 16;
    options.lutSize = 32;
    options.specularSamples = 128;
    options.irradianceSamples = 256;
    return options;
}

// One level and layer of an RGBA16Float texture as RGBA floats, rows top to bottom.
inline std::vector<float> readHalfTexels(gpu::Context& context,
                                         const wgpu::Texture& texture,
                                         std::uint32_t level,
                                         std::uint32_t layer) {
    auto texels = gpu::readTextureRgba16Float(context, texture, level, layer);
    EXPECT_TRUE(texels.ok()) << texels.error().message;
    return texels.ok() ? std::move(*texels) : std::vector<float>{};
}

// Runs a compute pipeline with one invocation per probe: `inputs` (floats) in a storage buffer
// at binding `inputBinding`, one vec4f result per probe read back from `outputBinding`, beside
// the caller's other group-0 entries. Returns each result's rgb.
inline std::vector<Vec3> runProbes(gpu::Context& context,
                                   const wgpu::ComputePipeline& pipeline,
                                   std::vector<wgpu::BindGroupEntry> entries,
                                   const std::vector<float>& inputs,
                                   std::size_t probeCount,
                                   std::uint32_t inputBinding,
                                   std::uint32_t outputBinding) {
    std::vector<Vec3> results;
    const std::uint64_t inSize = inputs.size() * sizeof(float);
    const std::uint64_t outSize = probeCount * 4 * sizeof(float);
    wgpu::BufferDescriptor descriptor{};
    descriptor.size = inSize;
    descriptor.usage = wgpu::BufferUsage::Storage | wgpu::BufferUsage::CopyDst;
    const wgpu::Buffer in = context.device().CreateBuffer(&descriptor);
    context.queue().WriteBuffer(in, 0, inputs.data(), inSize);
    descriptor.size = outSize;
    descriptor.usage = wgpu::BufferUsage::Storage | wgpu::BufferUsage::CopySrc;
    const wgpu::Buffer out = context.device().CreateBuffer(&descriptor);
    entries.push_back({});
    entries.back().binding = inputBinding;
    entries.back().buffer = in;
    entries.push_back({});
    entries.back().binding = outputBinding;
    entries.back().buffer = out;

    wgpu::BindGroupDescriptor groupDescriptor{};
    groupDescriptor.layout = pipeline.GetBindGroupLayout(0);
    groupDescriptor.entryCount = entries.size();
    groupDescriptor.entries = entries.data();
    const wgpu::BindGroup group = context.device().CreateBindGroup(&groupDescriptor);
    const wgpu::CommandEncoder encoder = context.device().CreateCommandEncoder();
    const wgpu::ComputePassEncoder pass = encoder.BeginComputePass();
    pass.SetPipeline(pipeline);
    pass.SetBindGroup(0, group);
    pass.DispatchWorkgroups(static_cast<std::uint32_t>(probeCount));
    pass.End();
    const wgpu::CommandBuffer commands = encoder.Finish();
    context.queue().Submit(1, &commands);
    auto bytes = gpu::readBuffer(context, out, 0, outSize);
    EXPECT_TRUE(bytes.ok()) << bytes.error().message;
    if (!bytes.ok()) {
        return results;
    }
    const auto* values = reinterpret_cast<const float*>(bytes->data());
    for (std::size_t i = 0; i < probeCount; ++i) {
        results.push_back({values[i * 4], values[i * 4 + 1], values[i * 4 + 2]});
    }
    return results;
}

// The "main" entry point of a compute shader given as WGSL text.
inline wgpu::ComputePipeline computePipeline(gpu::Context& context, const char* code) {
    wgpu::ShaderSourceWGSL wgsl;
    wgsl.code = code;
    wgpu::ShaderModuleDescriptor moduleDescriptor{};
    moduleDescriptor.nextInChain = &wgsl;
    wgpu::ComputePipelineDescriptor descriptor{};
    descriptor.compute.module = context.device().CreateShaderModule(&moduleDescriptor);
    descriptor.compute.entryPoint = "main";
    return context.device().CreateComputePipeline(&descriptor);
}

inline wgpu::BindGroupEntry textureBinding(std::uint32_t binding, const wgpu::TextureView& view) {
    wgpu::BindGroupEntry entry{};
    entry.binding = binding;
    entry.textureView = view;
    return entry;
}

inline wgpu::BindGroupEntry samplerBinding(std::uint32_t binding, const wgpu::Sampler& sampler) {
    wgpu::BindGroupEntry entry{};
    entry.binding = binding;
    entry.sampler = sampler;
    return entry;
}

// Samples cube views at given directions with a tiny compute shader, through the sampler the
// renderer will use: this checks the face convention end to end, not texel by texel.
class CubeProbe {
  public:
    explicit CubeProbe(gpu::Context& context) : mContext(context) {
        const char* code = R"(
@group(0) @binding(0) var cube: texture_cube<f32>;
@group(0) @binding(1) var cubeSampler: sampler;
@group(0) @binding(2) var<storage, read> directions: array<vec4f>;
@group(0) @binding(3) var<storage, read_write> results: array<vec4f>;
@compute @workgroup_size(1)
fn main(@builtin(global_invocation_id) id: vec3u) {
    let probe = directions[id.x];
    results[id.x] = textureSampleLevel(cube, cubeSampler, probe.xyz, probe.w);
}
)";
        mPipeline = computePipeline(context, code);
    }

    // The radiance toward each direction at `lod`.
    std::vector<Vec3> sample(const wgpu::TextureView& cube,
                             const wgpu::Sampler& sampler,
                             const std::vector<Vec3>& directions,
                             float lod) {
        std::vector<float> input;
        for (const Vec3& d : directions) {
            input.insert(input.end(), {d[0], d[1], d[2], lod});
        }
        return runProbes(mContext, mPipeline, {textureBinding(0, cube), samplerBinding(1, sampler)},
                         input, directions.size(), 2, 3);
    }

  private:
    gpu::Context& mContext;
    wgpu::ComputePipeline mPipeline;
};

// Looks the environment up exactly as the scene shaders do: a compute shader that includes
// scene_lighting.wgsl and calls its environmentRadiance, environmentIrradiance and brdfLutAt,
// bound to a SceneLighting's uniform and the atlas.
class AtlasProbe {
  public:
    enum class Lookup : std::uint32_t { Radiance, Irradiance, Brdf };

    explicit AtlasProbe(gpu::Context& context) : mContext(context) {
        const std::string probe = R"(
#include "scene_lighting.wgsl"
@group(0) @binding(5) var<storage, read> probes: array<vec4f>;  // (xyz, lod), (lookup, ...)
@group(0) @binding(6) var<storage, read_write> results: array<vec4f>;
@compute @workgroup_size(1)
fn main(@builtin(global_invocation_id) id: vec3u) {
    let probe = probes[2u * id.x];
    let lookup = u32(probes[2u * id.x + 1u].x);
    var value = vec3f(0.0);
    if (lookup == 0u) {
        value = environmentRadiance(normalize(probe.xyz), probe.w);
    } else if (lookup == 1u) {
        value = environmentIrradiance(normalize(probe.xyz));
    } else {
        value = brdfLutAt(probe.x, probe.y);
    }
    results[id.x] = vec4f(value, 1.0);
}
)";
        const shaders::FileLookup lookup =
            [&probe](std::string_view name) -> std::optional<std::string_view> {
            if (name == "probe.wgsl") {
                return probe;
            }
            for (const auto& file : shaders::wgslFiles()) {
                if (file.name == name) {
                    return file.contents;
                }
            }
            return std::nullopt;
        };
        auto source = shaders::composeShader("probe.wgsl", {}, lookup);
        EXPECT_TRUE(source.ok()) << source.error().message;
        if (!source.ok()) {
            return;
        }
        mPipeline = computePipeline(context, source->c_str());
    }

    // `lookup` at each direction (Brdf: x = NdotV, y = roughness), `lod` for Radiance.
    std::vector<Vec3> sample(const SceneLighting& lighting,
                             Lookup lookup,
                             const std::vector<Vec3>& directions,
                             float lod = 0.0f) {
        if (!mPipeline) {
            return {};
        }
        std::vector<float> input;
        for (const Vec3& d : directions) {
            input.insert(input.end(), {d[0], d[1], d[2], lod, float(lookup), 0, 0, 0});
        }
        wgpu::BindGroupEntry uniform{};
        uniform.binding = 1;
        uniform.buffer = lighting.uniformBuffer();
        const Environment& environment = lighting.environment();
        return runProbes(mContext, mPipeline,
                         {uniform, textureBinding(3, environment.atlasView()),
                          samplerBinding(4, environment.sampler())},
                         input, directions.size(), 5, 6);
    }

  private:
    gpu::Context& mContext;
    wgpu::ComputePipeline mPipeline;
};

inline Vec3 normalized(Vec3 v) {
    const float length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    return {v[0] / length, v[1] / length, v[2] / length};
}

// A panorama whose radiance toward d is (2, 2, 2) + scale * d in HdrImage's convention:
// distinct colours toward all six axes, and every face flip or rotation shows.
inline image::HdrImage directionalPanorama(std::uint32_t width, float scale = 1.0f) {
    image::HdrImage image;
    image.width = width;
    image.height = width / 2;
    for (std::uint32_t row = 0; row < image.height; ++row) {
        const float theta = kPi * (float(row) + 0.5f) / float(image.height);
        for (std::uint32_t column = 0; column < image.width; ++column) {
            const float phi = 2.0f * kPi * (float(column) + 0.5f) / float(image.width);
            const Vec3 d = {std::sin(theta) * std::cos(phi), std::cos(theta),
                            std::sin(theta) * std::sin(phi)};
            for (int c = 0; c < 3; ++c) {
                image.rgb.push_back(2.0f + scale * d[c]);
            }
        }
    }
    return image;
}

// The radiance of directionalPanorama at level 0: 2 + d toward every direction d.
inline void expectDirectional(const std::vector<Vec3>& values,
                              const std::vector<Vec3>& directions,
                              float tolerance,
                              const char* what) {
    ASSERT_EQ(values.size(), directions.size()) << what;
    for (std::size_t i = 0; i < directions.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(values[i][c], 2.0f + directions[i][c], tolerance)
                << what << ", direction " << i << " (" << directions[i][0] << ", "
                << directions[i][1] << ", " << directions[i][2] << ") channel " << c;
        }
    }
}

inline std::vector<Vec3> probeDirections() {
    std::vector<Vec3> directions = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                    {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
    // Off-axis directions too, in every octant, so a mirrored (sc, tc) within a face shows.
    for (int i = 0; i < 8; ++i) {
        directions.push_back(
            normalized({(i & 1) ? 0.8f : -0.8f, (i & 2) ? 0.45f : -0.45f, (i & 4) ? 0.3f : -0.3f}));
        directions.push_back(
            normalized({(i & 1) ? 0.2f : -0.2f, (i & 2) ? 0.9f : -0.9f, (i & 4) ? 0.5f : -0.5f}));
        directions.push_back(normalized(
            {(i & 1) ? 0.35f : -0.35f, (i & 2) ? 0.15f : -0.15f, (i & 4) ? 0.9f : -0.9f}));
    }
    return directions;
}

struct Fixture {
    explicit Fixture(gpu::Context& context) : shaders(context.device()) {}
    Result<Environment> create(gpu::Context& context,
                               const image::HdrImage& panorama,
                               const EnvironmentOptions& options = smallOptions()) {
        return Environment::create(context.device(), context.queue(), shaders, panorama, options);
    }
    shaders::ShaderLibrary shaders;
};

// On the cube's edges and corners, where a lookup crosses from one atlas cell to another, and a
// hair to either side: filtering must not show the seams.
inline std::vector<Vec3> seamDirections() {
    std::vector<Vec3> directions;
    for (float a : {1.0f, -1.0f}) {
        for (float b : {1.0f, -1.0f}) {
            for (float offset : {0.0f, 0.003f, -0.003f}) {
                directions.push_back(normalized({a, b + offset, 0.4f}));   // x-y edges.
                directions.push_back(normalized({a + offset, -0.3f, b}));  // x-z edges.
                directions.push_back(normalized({0.6f, a, b + offset}));   // y-z edges.
            }
            directions.push_back(normalized({a, b, 1.0f}));  // Corners.
            directions.push_back(normalized({a, b, -1.0f}));
        }
    }
    return directions;
}

inline Result<SceneLighting> lightingFor(gpu::Context& context, Environment&& environment) {
    return SceneLighting::create(context.device(), context.queue(),
                                 std::make_shared<Environment>(std::move(environment)));
}

}  // namespace encore::render::environment_test
