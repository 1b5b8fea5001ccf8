#include "render/EnvironmentAtlas.h"

#include <algorithm>

namespace encore::render {

EnvironmentAtlasLayout layoutEnvironmentAtlas(std::uint32_t specularFaceSize,
                                              std::uint32_t specularLevels,
                                              std::uint32_t irradianceFaceSize,
                                              std::uint32_t brdfSize) {
    EnvironmentAtlasLayout layout;
    for (std::uint32_t level = 0; level < specularLevels; ++level) {
        layout.specular.push_back({0, 0, std::max(specularFaceSize >> level, 1u), 6});
    }
    layout.irradiance = {0, 0, std::max(irradianceFaceSize, 1u), 6};
    layout.brdf = {0, 0, std::max(brdfSize, 1u), 1};

    std::vector<AtlasRegion*> regions;
    for (AtlasRegion& level : layout.specular) {
        regions.push_back(&level);
    }
    regions.push_back(&layout.irradiance);
    regions.push_back(&layout.brdf);
    // Stable, so equal heights keep the order above.
    std::stable_sort(
        regions.begin(), regions.end(),
        [](const AtlasRegion* a, const AtlasRegion* b) { return a->height() > b->height(); });
    std::uint32_t shelfWidth = 0;
    for (const AtlasRegion* region : regions) {
        shelfWidth = std::max(shelfWidth, region->width());
    }

    std::uint32_t shelfY = 0;
    std::uint32_t shelfHeight = 0;
    std::uint32_t shelfX = 0;
    for (AtlasRegion* region : regions) {
        if (shelfX + region->width() > shelfWidth) {
            shelfY += shelfHeight;
            shelfX = 0;
            shelfHeight = 0;
        }
        region->x = shelfX;
        region->y = shelfY;
        shelfX += region->width();
        shelfHeight = std::max(shelfHeight, region->height());
    }
    layout.width = shelfWidth;
    layout.height = shelfY + shelfHeight;
    return layout;
}

EnvironmentAtlasUniform makeEnvironmentAtlasUniform(const EnvironmentAtlasLayout& layout) {
    EnvironmentAtlasUniform uniform{};
    uniform.inverseSize[0] = layout.width ? 1.0f / float(layout.width) : 0.0f;
    uniform.inverseSize[1] = layout.height ? 1.0f / float(layout.height) : 0.0f;
    auto write = [](const AtlasRegion& region, float(&out)[4]) {
        out[0] = float(region.x);
        out[1] = float(region.y);
        out[2] = float(region.size);
        out[3] = 0.0f;
    };
    write(layout.irradiance, uniform.irradiance);
    write(layout.brdf, uniform.brdf);
    const std::size_t levels =
        std::min<std::size_t>(layout.specular.size(), EnvironmentAtlasLayout::kMaxSpecularLevels);
    for (std::size_t level = 0; level < levels; ++level) {
        write(layout.specular[level], uniform.specular[level]);
    }
    return uniform;
}

}  // namespace encore::render
