#pragma once

// Where each map of image-based lighting lies in the environment atlas, the one texture the
// scene shaders sample (environment_atlas.wgsl says why one and how it is addressed). Pure
// arithmetic, no WebGPU: Environment packs the atlas by this layout, and SceneLighting hands it
// to the shaders in the lighting uniform.
//
// A cube map level is a region of six cells (3 x 2), the BRDF table a region of one; every cell
// is its face or table with a one-texel border.

#include <cstdint>
#include <vector>

namespace encore::render {

struct AtlasRegion {
    std::uint32_t x = 0;  // First texel, borders included.
    std::uint32_t y = 0;
    std::uint32_t size = 0;   // Interior texels per side of one cell.
    std::uint32_t cells = 1;  // 6: a cube map level (3 x 2 cells); 1: a table.

    std::uint32_t cellSpan() const { return size + 2; }
    std::uint32_t width() const { return (cells == 6 ? 3 : 1) * cellSpan(); }
    std::uint32_t height() const { return (cells == 6 ? 2 : 1) * cellSpan(); }
};

struct EnvironmentAtlasLayout {
    // The lighting uniform has room for this many specular levels (scene_lighting.wgsl).
    static constexpr std::uint32_t kMaxSpecularLevels = 8;

    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::vector<AtlasRegion> specular;  // One per roughness level, level 0 a mirror.
    AtlasRegion irradiance;
    AtlasRegion brdf;
};

// Shelves as wide as the mirror level, regions tallest first. Deterministic: the same sizes
// always give the same layout.
EnvironmentAtlasLayout layoutEnvironmentAtlas(std::uint32_t specularFaceSize,
                                              std::uint32_t specularLevels,
                                              std::uint32_t irradianceFaceSize,
                                              std::uint32_t brdfSize);

// struct EnvironmentAtlasLayout of environment_atlas.wgsl, byte for byte: each region as
// (first texel x, y, cell interior size, 0).
struct EnvironmentAtlasUniform {
    float inverseSize[2];
    float unused[2];
    float irradiance[4];
    float brdf[4];
    float specular[EnvironmentAtlasLayout::kMaxSpecularLevels][4];
};
static_assert(sizeof(EnvironmentAtlasUniform) == 176);

EnvironmentAtlasUniform makeEnvironmentAtlasUniform(const EnvironmentAtlasLayout& layout);

}  // namespace encore::render
