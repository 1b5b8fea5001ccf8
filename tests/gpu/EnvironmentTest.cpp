#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include "GpuTestSupport.h"
#include "encore/image/HdrImage.h"
#include "encore/render/Environment.h"
#include "encore/render/Lighting.h"
#include "gpu/Readback.h"
#include "shaders/EmbeddedFiles.h"
#include "shaders/ShaderComposer.h"

namespace encore::render {
namespace {

using Vec3 = std::array<float, 3>;
constexpr float kPi = std::numbers::pi_v<float>;

// Small maps: every property tested here holds at any size, and lavapipe is a CPU.
EnvironmentOptions smallOptions() {
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
std::vector<float> readHalfTexels(gpu::Context& context,
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
std::vector<Vec3> runProbes(gpu::Context& context,
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
wgpu::ComputePipeline computePipeline(gpu::Context& context, const char* code) {
    wgpu::ShaderSourceWGSL wgsl;
    wgsl.code = code;
    wgpu::ShaderModuleDescriptor moduleDescriptor{};
    moduleDescriptor.nextInChain = &wgsl;
    wgpu::ComputePipelineDescriptor descriptor{};
    descriptor.compute.module = context.device().CreateShaderModule(&moduleDescriptor);
    descriptor.compute.entryPoint = "main";
    return context.device().CreateComputePipeline(&descriptor);
}

wgpu::BindGroupEntry textureBinding(std::uint32_t binding, const wgpu::TextureView& view) {
    wgpu::BindGroupEntry entry{};
    entry.binding = binding;
    entry.textureView = view;
    return entry;
}

wgpu::BindGroupEntry samplerBinding(std::uint32_t binding, const wgpu::Sampler& sampler) {
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

Vec3 normalized(Vec3 v) {
    const float length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    return {v[0] / length, v[1] / length, v[2] / length};
}

// A panorama whose radiance toward d is (2, 2, 2) + scale * d in HdrImage's convention:
// distinct colours toward all six axes, and every face flip or rotation shows.
image::HdrImage directionalPanorama(std::uint32_t width, float scale = 1.0f) {
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
void expectDirectional(const std::vector<Vec3>& values,
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

std::vector<Vec3> probeDirections() {
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
std::vector<Vec3> seamDirections() {
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

Result<SceneLighting> lightingFor(gpu::Context& context, Environment&& environment) {
    return SceneLighting::create(context.device(), context.queue(),
                                 std::make_shared<Environment>(std::move(environment)));
}

TEST(EnvironmentTest, UniformEnvironmentStaysUniform) {
    ENCORE_REQUIRE_VULKAN(context);
    Fixture fixture(*context);
    const Vec3 radiance = {0.8f, 1.0f, 1.25f};
    auto environment = fixture.create(
        *context, image::makeUniformEnvironment(radiance[0], radiance[1], radiance[2]));
    ASSERT_TRUE(environment.ok()) << environment.error().message;
    ASSERT_TRUE(context->checkNoErrors("environment").ok());

    auto expectUniform = [&](const wgpu::Texture& texture, std::uint32_t level, const char* name) {
        float worst = 0.0f;
        for (std::uint32_t face = 0; face < 6; ++face) {
            const std::vector<float> texels = readHalfTexels(*context, texture, level, face);
            ASSERT_FALSE(texels.empty());
            for (std::size_t i = 0; i < texels.size(); i += 4) {
                for (int c = 0; c < 3; ++c) {
                    worst = std::max(worst, std::fabs(texels[i + c] / radiance[c] - 1.0f));
                }
            }
        }
        EXPECT_LT(worst, 0.015f) << name << " level " << level;
    };
    for (std::uint32_t level = 0; level < environment->specularLevels(); ++level) {
        expectUniform(environment->specularTexture(), level, "specular");
    }
    expectUniform(environment->irradianceTexture(), 0, "irradiance");
    EXPECT_EQ(environment->specularTexture().GetMipLevelCount(), 5u);
    EXPECT_EQ(environment->specularTexture().GetFormat(), Environment::kCubeFormat);
    EXPECT_EQ(environment->specularTexture().GetDepthOrArrayLayers(), 6u);
    EXPECT_TRUE(context->checkNoErrors("environment readback").ok());
}

TEST(EnvironmentTest, CubeFacesFollowThePanoramaConvention) {
    ENCORE_REQUIRE_VULKAN(context);
    Fixture fixture(*context);
    auto environment = fixture.create(*context, directionalPanorama(256));
    ASSERT_TRUE(environment.ok()) << environment.error().message;
    CubeProbe probe(*context);
    const std::vector<Vec3> directions = probeDirections();

    // Level 0 is the panorama itself.
    expectDirectional(
        probe.sample(environment->specularView(), environment->sampler(), directions, 0.0f),
        directions, 0.03f, "cube mirror level");

    // The cosine-weighted average of d over the hemisphere around n is (2/3) n, so the
    // irradiance of this panorama is exactly 2 + (2/3) n.
    const auto irradiance =
        probe.sample(environment->irradianceView(), environment->sampler(), directions, 0.0f);
    ASSERT_EQ(irradiance.size(), directions.size());
    for (std::size_t i = 0; i < directions.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(irradiance[i][c], 2.0f + 2.0f / 3.0f * directions[i][c], 0.04f)
                << "irradiance, direction " << i << " channel " << c;
        }
    }

    // Rougher levels average over wider lobes: still 2 + c n, with c shrinking as roughness
    // grows, and never pointing elsewhere.
    float previous = 1.0f;
    for (std::uint32_t level = 1; level < environment->specularLevels(); ++level) {
        const auto blurred = probe.sample(environment->specularView(), environment->sampler(),
                                          directions, float(level));
        ASSERT_EQ(blurred.size(), directions.size());
        const float c = blurred[0][0] - 2.0f;  // Toward +X.
        EXPECT_LE(c, previous + 0.02f) << "level " << level;
        EXPECT_GT(c, 0.3f) << "level " << level;
        for (std::size_t i = 0; i < directions.size(); ++i) {
            for (int k = 0; k < 3; ++k) {
                EXPECT_NEAR(blurred[i][k], 2.0f + c * directions[i][k], 0.05f)
                    << "level " << level << ", direction " << i << " channel " << k;
            }
        }
        previous = c;
    }
    EXPECT_TRUE(context->checkNoErrors("environment orientation").ok());
}

// The LUT's integrals by brute-force quadrature over the hemisphere of light directions (no
// importance sampling), for rough enough lobes that a fine grid resolves them.
Vec3 referenceLut(double nDotV, double roughness) {
    const double alpha = roughness * roughness;
    const double a2 = alpha * alpha;
    const double vx = std::sqrt(1.0 - nDotV * nDotV);
    const int steps = 400;
    double scale = 0.0;
    double bias = 0.0;
    double sheen = 0.0;
    for (int i = 0; i < steps; ++i) {
        const double theta = (i + 0.5) / steps * std::numbers::pi / 2.0;
        for (int j = 0; j < 2 * steps; ++j) {
            const double phi = (j + 0.5) / (2 * steps) * 2.0 * std::numbers::pi;
            const double lx = std::sin(theta) * std::cos(phi);
            const double ly = std::sin(theta) * std::sin(phi);
            const double nDotL = std::cos(theta);
            const double hLength =
                std::sqrt((lx + vx) * (lx + vx) + ly * ly + (nDotL + nDotV) * (nDotL + nDotV));
            const double nDotH = (nDotL + nDotV) / hLength;
            const double vDotH = (vx * (lx + vx) + nDotV * (nDotL + nDotV)) / hLength;
            const double solidAngle =
                std::sin(theta) * (std::numbers::pi / 2.0 / steps) * (std::numbers::pi / steps);
            const double f = nDotH * nDotH * (a2 - 1.0) + 1.0;
            const double d = a2 / (std::numbers::pi * f * f);
            const double visibility = 0.5 / (nDotL * std::sqrt(nDotV * nDotV * (1.0 - a2) + a2) +
                                             nDotV * std::sqrt(nDotL * nDotL * (1.0 - a2) + a2));
            const double fresnel = std::pow(1.0 - vDotH, 5.0);
            scale += d * visibility * (1.0 - fresnel) * nDotL * solidAngle;
            bias += d * visibility * fresnel * nDotL * solidAngle;
            const double sin2h = std::max(1.0 - nDotH * nDotH, 0.0078125);
            const double charlie =
                (2.0 + 1.0 / alpha) * std::pow(sin2h, 0.5 / alpha) / (2.0 * std::numbers::pi);
            sheen += charlie / (4.0 * (nDotL + nDotV - nDotL * nDotV)) * nDotL * solidAngle;
        }
    }
    return {float(scale), float(bias), float(std::min(sheen, 1.0))};
}

TEST(EnvironmentTest, BrdfLutIsPlausible) {
    ENCORE_REQUIRE_VULKAN(context);
    Fixture fixture(*context);
    EnvironmentOptions options = smallOptions();
    options.lutSize = 64;
    auto environment =
        fixture.create(*context, image::makeUniformEnvironment(1, 1, 1, 16), options);
    ASSERT_TRUE(environment.ok()) << environment.error().message;
    const std::uint32_t size = environment->brdfLutTexture().GetWidth();
    ASSERT_EQ(size, 64u);
    const std::vector<float> lut = readHalfTexels(*context, environment->brdfLutTexture(), 0, 0);
    ASSERT_EQ(lut.size(), std::size_t(size) * size * 4);
    // u = NdotV across, v = roughness down.
    auto at = [&](std::uint32_t nDotV, std::uint32_t roughness, int channel) {
        return lut[(std::size_t(roughness) * size + nDotV) * 4 + channel];
    };
    auto total = [&](std::uint32_t nDotV, std::uint32_t roughness) {
        return at(nDotV, roughness, 0) + at(nDotV, roughness, 1);
    };
    // A mirror seen head-on reflects everything: scale + bias = 1.
    EXPECT_NEAR(total(size - 1, 0), 1.0f, 0.01f);
    // Grazing mirrors are all Fresnel bias.
    EXPECT_GT(at(0, 0, 1), at(size - 1, 0, 1));
    for (std::uint32_t roughness = 0; roughness < size; ++roughness) {
        for (std::uint32_t nDotV = 0; nDotV < size; ++nDotV) {
            ASSERT_GE(at(nDotV, roughness, 0), 0.0f);
            ASSERT_GE(at(nDotV, roughness, 1), 0.0f);
            ASSERT_LE(total(nDotV, roughness), 1.005f) << nDotV << ", " << roughness;
            ASSERT_GE(at(nDotV, roughness, 2), 0.0f) << nDotV << ", " << roughness;
            ASSERT_LE(at(nDotV, roughness, 2), 1.0f) << nDotV << ", " << roughness;
        }
        if (roughness > 0) {
            // Rougher surfaces lose energy to masking and shadowing.
            EXPECT_LE(total(size - 1, roughness), total(size - 1, roughness - 1) + 0.005f)
                << "roughness row " << roughness;
        }
    }
    EXPECT_LT(total(size - 1, size - 1), 0.95f);
    // Sheen: a rough sheen reflects noticeably.
    EXPECT_GT(at(size / 2, size - 1, 2), 0.05f);
    // Against quadrature, at pixel centres.
    for (auto [column, row] : {std::pair{16u, 32u}, std::pair{48u, 48u}, std::pair{40u, 22u},
                               std::pair{8u, 60u}, std::pair{60u, 40u}}) {
        const Vec3 expected = referenceLut((column + 0.5) / size, (row + 0.5) / size);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(at(column, row, c), expected[c], 0.01f + 0.02f * expected[c])
                << "NdotV texel " << column << ", roughness texel " << row << ", channel " << c;
        }
    }
    EXPECT_TRUE(context->checkNoErrors("environment LUT").ok());
}

TEST(EnvironmentTest, LoadReplacesContentsInTheSameTextures) {
    ENCORE_REQUIRE_VULKAN(context);
    Fixture fixture(*context);
    auto environment = fixture.create(*context, image::makeUniformEnvironment(1, 1, 1, 64));
    ASSERT_TRUE(environment.ok()) << environment.error().message;
    const WGPUTextureView specularView = environment->specularView().Get();
    const WGPUTextureView irradianceView = environment->irradianceView().Get();
    const WGPUTextureView lutView = environment->brdfLutView().Get();
    const WGPUTexture specular = environment->specularTexture().Get();
    const WGPUTexture atlas = environment->atlasTexture().Get();
    const WGPUTextureView atlasView = environment->atlasView().Get();
    const WGPUSampler sampler = environment->sampler().Get();
    const std::vector<float> lutBefore =
        readHalfTexels(*context, environment->brdfLutTexture(), 0, 0);

    // A different size and radiance.
    ASSERT_TRUE(environment->load(image::makeUniformEnvironment(3, 3, 3, 200)).ok());
    EXPECT_EQ(environment->specularView().Get(), specularView);
    EXPECT_EQ(environment->irradianceView().Get(), irradianceView);
    EXPECT_EQ(environment->brdfLutView().Get(), lutView);
    EXPECT_EQ(environment->specularTexture().Get(), specular);
    EXPECT_EQ(environment->atlasTexture().Get(), atlas);
    EXPECT_EQ(environment->atlasView().Get(), atlasView);
    EXPECT_EQ(environment->sampler().Get(), sampler);
    for (std::uint32_t level : {0u, 2u, 4u}) {
        const auto texels = readHalfTexels(*context, environment->specularTexture(), level, 3);
        ASSERT_FALSE(texels.empty());
        EXPECT_NEAR(texels[0], 3.0f, 0.05f) << "level " << level;
    }
    const auto irradiance = readHalfTexels(*context, environment->irradianceTexture(), 0, 1);
    ASSERT_FALSE(irradiance.empty());
    EXPECT_NEAR(irradiance[4 * 5 + 1], 3.0f, 0.05f);
    EXPECT_EQ(readHalfTexels(*context, environment->brdfLutTexture(), 0, 0), lutBefore);

    // And back to a directional one of yet another size: the probe sees it.
    ASSERT_TRUE(environment->load(directionalPanorama(128)).ok());
    CubeProbe probe(*context);
    const auto mirror =
        probe.sample(environment->specularView(), environment->sampler(), {{0, 0, -1}}, 0.0f);
    ASSERT_EQ(mirror.size(), 1u);
    EXPECT_NEAR(mirror[0][2], 1.0f, 0.05f);
    EXPECT_GT(environment->lastBuildMilliseconds(), 0.0);
    // What the shaders see, through the atlas, is the new panorama too.
    auto lighting = lightingFor(*context, std::move(*environment));
    ASSERT_TRUE(lighting.ok()) << lighting.error().message;
    const auto seen =
        AtlasProbe(*context).sample(*lighting, AtlasProbe::Lookup::Radiance, {{0, 0, -1}}, 0.0f);
    ASSERT_EQ(seen.size(), 1u);
    EXPECT_NEAR(seen[0][2], 1.0f, 0.05f);
    EXPECT_TRUE(context->checkNoErrors("environment load").ok());
}

TEST(EnvironmentTest, RefusesBadOptionsAndPanoramas) {
    ENCORE_REQUIRE_VULKAN(context);
    Fixture fixture(*context);
    EnvironmentOptions options = smallOptions();
    options.specularLevels = 20;  // More than 64's chain of 7.
    auto tooManyLevels = fixture.create(*context, image::makeUniformEnvironment(1, 1, 1), options);
    ASSERT_FALSE(tooManyLevels.ok());
    EXPECT_EQ(tooManyLevels.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(tooManyLevels.error().message.find("specularLevels"), std::string::npos);

    options = smallOptions();
    options.specularSize = 1024;
    options.specularLevels = 9;  // The chain has 11, the lighting uniform room for 8.
    auto pastUniform = fixture.create(*context, image::makeUniformEnvironment(1, 1, 1), options);
    ASSERT_FALSE(pastUniform.ok());
    EXPECT_NE(pastUniform.error().message.find("at most 8"), std::string::npos)
        << pastUniform.error().message;

    options = smallOptions();
    options.irradianceSamples = 0;
    EXPECT_FALSE(fixture.create(*context, image::makeUniformEnvironment(1, 1, 1), options).ok());

    image::HdrImage broken = image::makeUniformEnvironment(1, 1, 1);
    broken.rgb.pop_back();
    auto inconsistent = fixture.create(*context, broken);
    ASSERT_FALSE(inconsistent.ok());
    EXPECT_EQ(inconsistent.error().code, ErrorCode::InvalidArgument);

    auto environment = fixture.create(*context, image::makeUniformEnvironment(1, 1, 1));
    ASSERT_TRUE(environment.ok()) << environment.error().message;
    EXPECT_FALSE(environment->load(image::HdrImage{}).ok());
    EXPECT_TRUE(context->checkNoErrors("environment refusals").ok());
}

TEST(EnvironmentTest, AtlasIsOneSubresourceHoldingEveryMap) {
    ENCORE_REQUIRE_VULKAN(context);
    Fixture fixture(*context);
    const Vec3 radiance = {0.8f, 1.0f, 1.25f};
    auto environment = fixture.create(
        *context, image::makeUniformEnvironment(radiance[0], radiance[1], radiance[2]));
    ASSERT_TRUE(environment.ok()) << environment.error().message;
    const wgpu::Texture& atlas = environment->atlasTexture();
    EXPECT_EQ(atlas.GetMipLevelCount(), 1u);
    EXPECT_EQ(atlas.GetDepthOrArrayLayers(), 1u);
    EXPECT_EQ(atlas.GetFormat(), wgpu::TextureFormat::RGBA16Float);
    const EnvironmentAtlasLayout& layout = environment->atlasLayout();
    EXPECT_EQ(atlas.GetWidth(), layout.width);
    EXPECT_EQ(atlas.GetHeight(), layout.height);
    ASSERT_EQ(layout.specular.size(), 5u);

    // Every texel of every cube cell, borders included, holds the uniform radiance.
    const std::vector<float> texels = readHalfTexels(*context, atlas, 0, 0);
    ASSERT_EQ(texels.size(), std::size_t(layout.width) * layout.height * 4);
    auto worstIn = [&](const AtlasRegion& region) {
        float worst = 0.0f;
        for (std::uint32_t y = region.y; y < region.y + region.height(); ++y) {
            for (std::uint32_t x = region.x; x < region.x + region.width(); ++x) {
                for (int c = 0; c < 3; ++c) {
                    const float value = texels[(std::size_t(y) * layout.width + x) * 4 + c];
                    worst = std::max(worst, std::fabs(value / radiance[c] - 1.0f));
                }
            }
        }
        return worst;
    };
    for (std::size_t level = 0; level < layout.specular.size(); ++level) {
        EXPECT_LT(worstIn(layout.specular[level]), 0.015f) << "specular level " << level;
    }
    EXPECT_LT(worstIn(layout.irradiance), 0.015f) << "irradiance";

    // The table region is the table, its border repeating the edge texels.
    const std::vector<float> lut = readHalfTexels(*context, environment->brdfLutTexture(), 0, 0);
    const std::uint32_t size = environment->brdfLutTexture().GetWidth();
    ASSERT_EQ(layout.brdf.size, size);
    for (std::uint32_t y = 0; y < size + 2; ++y) {
        for (std::uint32_t x = 0; x < size + 2; ++x) {
            const std::uint32_t sx = std::clamp(int(x) - 1, 0, int(size) - 1);
            const std::uint32_t sy = std::clamp(int(y) - 1, 0, int(size) - 1);
            for (int c = 0; c < 4; ++c) {
                ASSERT_EQ(
                    texels[(std::size_t(layout.brdf.y + y) * layout.width + layout.brdf.x + x) * 4 +
                           c],
                    lut[(std::size_t(sy) * size + sx) * 4 + c])
                    << "table texel " << x << ", " << y << " channel " << c;
            }
        }
    }
    EXPECT_TRUE(context->checkNoErrors("environment atlas").ok());
}

TEST(EnvironmentTest, AtlasLookupsMatchTheMapsTheyPack) {
    ENCORE_REQUIRE_VULKAN(context);
    Fixture fixture(*context);
    // Faces of at least 8 texels at every level: on a 4-texel face the cube's own filtering
    // across edges (three texels meet at a corner) and the atlas's borders differ by more
    // than the tolerance, though both are smooth.
    EnvironmentOptions options = smallOptions();
    options.specularSize = 128;
    auto environment = fixture.create(*context, directionalPanorama(256), options);
    ASSERT_TRUE(environment.ok()) << environment.error().message;
    const wgpu::TextureView specularCube = environment->specularView();
    const wgpu::TextureView irradianceCube = environment->irradianceView();
    const wgpu::Sampler sampler = environment->sampler();
    const std::uint32_t levels = environment->specularLevels();
    auto lighting = lightingFor(*context, std::move(*environment));
    ASSERT_TRUE(lighting.ok()) << lighting.error().message;
    CubeProbe cubes(*context);
    AtlasProbe atlas(*context);
    std::vector<Vec3> directions = probeDirections();
    const std::vector<Vec3> seams = seamDirections();
    directions.insert(directions.end(), seams.begin(), seams.end());

    // The mirror level is the panorama, 2 + d, across cube edges and corners as anywhere else.
    expectDirectional(atlas.sample(*lighting, AtlasProbe::Lookup::Radiance, directions, 0.0f),
                      directions, 0.03f, "atlas mirror level");
    // Every level, and between levels, as the cube's own trilinear lookup gives it.
    for (float lod : {0.0f, 1.0f, 1.5f, 2.0f, 3.25f, float(levels - 1)}) {
        const auto expected = cubes.sample(specularCube, sampler, directions, lod);
        const auto actual = atlas.sample(*lighting, AtlasProbe::Lookup::Radiance, directions, lod);
        ASSERT_EQ(actual.size(), directions.size());
        for (std::size_t i = 0; i < directions.size(); ++i) {
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(actual[i][c], expected[i][c], 0.02f)
                    << "lod " << lod << ", direction " << i << " channel " << c;
            }
        }
    }
    const auto expectedIrradiance = cubes.sample(irradianceCube, sampler, directions, 0.0f);
    const auto irradiance = atlas.sample(*lighting, AtlasProbe::Lookup::Irradiance, directions);
    ASSERT_EQ(irradiance.size(), directions.size());
    for (std::size_t i = 0; i < directions.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(irradiance[i][c], 2.0f + 2.0f / 3.0f * directions[i][c], 0.04f)
                << "irradiance, direction " << i << " channel " << c;
            EXPECT_NEAR(irradiance[i][c], expectedIrradiance[i][c], 0.02f)
                << "irradiance against the cube, direction " << i << " channel " << c;
        }
    }

    // The table: texel centres give the texels, and outside 0..1 the edge (clamped).
    const Environment& packed = lighting->environment();
    const std::uint32_t size = packed.brdfLutTexture().GetWidth();
    const std::vector<float> lut = readHalfTexels(*context, packed.brdfLutTexture(), 0, 0);
    std::vector<Vec3> coordinates;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> texelsAt;
    for (auto [x, y] : {std::pair{0u, 0u}, std::pair{5u, 9u}, std::pair{size - 1, 3u},
                        std::pair{17u, size - 1}, std::pair{size - 1, size - 1}}) {
        coordinates.push_back({(x + 0.5f) / size, (y + 0.5f) / size, 0.0f});
        texelsAt.emplace_back(x, y);
    }
    coordinates.push_back({0.0f, 0.0f, 0.0f});
    texelsAt.emplace_back(0, 0);
    coordinates.push_back({1.0f, 1.0f, 0.0f});
    texelsAt.emplace_back(size - 1, size - 1);
    const auto table = atlas.sample(*lighting, AtlasProbe::Lookup::Brdf, coordinates);
    ASSERT_EQ(table.size(), coordinates.size());
    for (std::size_t i = 0; i < coordinates.size(); ++i) {
        const auto [x, y] = texelsAt[i];
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(table[i][c], lut[(std::size_t(y) * size + x) * 4 + c], 1e-3f)
                << "table at " << coordinates[i][0] << ", " << coordinates[i][1] << " channel "
                << c;
        }
    }
    EXPECT_TRUE(context->checkNoErrors("environment atlas lookups").ok());
}

// Prints how long the default maps take from the studio panorama (not asserted: lavapipe's
// speed depends on the machine).
TEST(EnvironmentTest, DefaultBuildTime) {
    ENCORE_REQUIRE_VULKAN(context);
    Fixture fixture(*context);
    const image::HdrImage studio = image::makeStudioEnvironment(512);
    auto environment = fixture.create(*context, studio, EnvironmentOptions{});
    ASSERT_TRUE(environment.ok()) << environment.error().message;
    const double createMs = environment->lastBuildMilliseconds();
    ASSERT_TRUE(environment->load(studio).ok());
    const double loadMs = environment->lastBuildMilliseconds();
    std::printf(
        "[ timing   ] Environment::create (defaults, studio 512x256): %.1f ms; "
        "load: %.1f ms on %s\n",
        createMs, loadMs, context->adapterDescription().summary().c_str());
    // The studio's sun is the brightest direction of the mirror level and survives into the
    // irradiance as a warm, bright upper hemisphere.
    CubeProbe probe(*context);
    const auto irradiance = probe.sample(environment->irradianceView(), environment->sampler(),
                                         {{0, 1, 0}, {0, -1, 0}}, 0.0f);
    ASSERT_EQ(irradiance.size(), 2u);
    EXPECT_GT(irradiance[0][1], irradiance[1][1]);
    for (const Vec3& value : irradiance) {
        for (float channel : value) {
            EXPECT_TRUE(std::isfinite(channel));
            EXPECT_GT(channel, 0.0f);
        }
    }
    EXPECT_TRUE(context->checkNoErrors("environment defaults").ok());
}

}  // namespace
}  // namespace encore::render
