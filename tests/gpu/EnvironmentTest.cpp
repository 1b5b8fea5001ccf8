#include <gtest/gtest.h>

#include "EnvironmentTestSupport.h"

namespace encore::render {
namespace {

using namespace environment_test;

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
