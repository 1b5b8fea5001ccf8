// The environment atlas: one texture holding every map, and lookups equal to the maps it packs.

#include <gtest/gtest.h>

#include "EnvironmentTestSupport.h"

namespace encore::render {
namespace {

using namespace environment_test;

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

}  // namespace
}  // namespace encore::render
