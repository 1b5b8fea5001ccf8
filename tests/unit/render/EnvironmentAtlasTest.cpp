#include <gtest/gtest.h>

#include <algorithm>
#include <tuple>
#include <vector>

#include "render/EnvironmentAtlas.h"

namespace encore::render {
namespace {

std::vector<AtlasRegion> regionsOf(const EnvironmentAtlasLayout& layout) {
    std::vector<AtlasRegion> regions = layout.specular;
    regions.push_back(layout.irradiance);
    regions.push_back(layout.brdf);
    return regions;
}

bool overlap(const AtlasRegion& a, const AtlasRegion& b) {
    return a.x < b.x + b.width() && b.x < a.x + a.width() && a.y < b.y + b.height() &&
           b.y < a.y + a.height();
}

void expectPacked(const EnvironmentAtlasLayout& layout) {
    const std::vector<AtlasRegion> regions = regionsOf(layout);
    for (std::size_t i = 0; i < regions.size(); ++i) {
        EXPECT_LE(regions[i].x + regions[i].width(), layout.width) << "region " << i;
        EXPECT_LE(regions[i].y + regions[i].height(), layout.height) << "region " << i;
        for (std::size_t j = i + 1; j < regions.size(); ++j) {
            EXPECT_FALSE(overlap(regions[i], regions[j])) << "regions " << i << " and " << j;
        }
    }
}

TEST(EnvironmentAtlasTest, DefaultSizesPackWithoutOverlap) {
    const EnvironmentAtlasLayout layout = layoutEnvironmentAtlas(256, 5, 32, 128);
    ASSERT_EQ(layout.specular.size(), 5u);
    // Cube levels as six cells of their face size, each with a one-texel border.
    EXPECT_EQ(layout.specular[0].size, 256u);
    EXPECT_EQ(layout.specular[0].width(), 3u * 258u);
    EXPECT_EQ(layout.specular[0].height(), 2u * 258u);
    EXPECT_EQ(layout.specular[4].size, 16u);
    EXPECT_EQ(layout.irradiance.size, 32u);
    EXPECT_EQ(layout.irradiance.cells, 6u);
    EXPECT_EQ(layout.brdf.size, 128u);
    EXPECT_EQ(layout.brdf.cells, 1u);
    EXPECT_EQ(layout.brdf.width(), 130u);
    EXPECT_EQ(layout.specular[0].x, 0u);
    EXPECT_EQ(layout.specular[0].y, 0u);
    expectPacked(layout);
    EXPECT_EQ(layout.width, 3u * 258u);  // As wide as the mirror level.
    // No more than a fifth of the atlas is unused.
    std::uint64_t used = 0;
    for (const AtlasRegion& region : regionsOf(layout)) {
        used += std::uint64_t(region.width()) * region.height();
    }
    EXPECT_GT(used * 5, std::uint64_t(layout.width) * layout.height * 4);
}

TEST(EnvironmentAtlasTest, OddAndTinySizesStillPack) {
    for (const auto& [specular, levels, irradiance, table] :
         {std::tuple{64u, 7u, 16u, 32u}, std::tuple{1u, 1u, 1u, 1u},
          std::tuple{100u, 4u, 50u, 300u}, std::tuple{8u, 4u, 64u, 16u}}) {
        const EnvironmentAtlasLayout layout =
            layoutEnvironmentAtlas(specular, levels, irradiance, table);
        ASSERT_EQ(layout.specular.size(), levels);
        EXPECT_EQ(layout.specular.back().size, std::max(specular >> (levels - 1), 1u));
        expectPacked(layout);
    }
}

TEST(EnvironmentAtlasTest, UniformHoldsEveryRegion) {
    const EnvironmentAtlasLayout layout = layoutEnvironmentAtlas(64, 3, 16, 32);
    const EnvironmentAtlasUniform uniform = makeEnvironmentAtlasUniform(layout);
    EXPECT_FLOAT_EQ(uniform.inverseSize[0], 1.0f / float(layout.width));
    EXPECT_FLOAT_EQ(uniform.inverseSize[1], 1.0f / float(layout.height));
    for (std::size_t level = 0; level < 3; ++level) {
        EXPECT_EQ(uniform.specular[level][0], float(layout.specular[level].x));
        EXPECT_EQ(uniform.specular[level][1], float(layout.specular[level].y));
        EXPECT_EQ(uniform.specular[level][2], float(layout.specular[level].size));
    }
    EXPECT_EQ(uniform.specular[3][2], 0.0f);  // Unused levels stay zero.
    EXPECT_EQ(uniform.irradiance[0], float(layout.irradiance.x));
    EXPECT_EQ(uniform.brdf[2], float(layout.brdf.size));
}

}  // namespace
}  // namespace encore::render
