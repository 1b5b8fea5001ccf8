#include "encore/batch/ViewStrips.h"

#include <algorithm>
#include <cstring>

namespace encore::batch {

StripLayout stripLayout(std::uint32_t width,
                        std::uint32_t height,
                        std::uint32_t views,
                        const gpu::DeviceLimits& limits) {
    StripLayout layout;
    layout.width = std::max(width, 1u);
    layout.height = std::max(height, 1u);
    views = std::max(views, 1u);
    std::uint64_t fit = std::max(1u, limits.maxTextureDimension2D / layout.width);
    // The read-back buffer holds the whole target, rows padded to 256 bytes.
    const std::uint64_t bytesPerStrip = std::uint64_t(layout.width) * 4 * layout.height;
    const std::uint64_t padding = std::uint64_t(256) * layout.height;
    fit =
        std::max<std::uint64_t>(1, std::min(fit, limits.maxBufferSize / (bytesPerStrip + padding)));
    const std::uint64_t targets = (views + fit - 1) / fit;
    layout.strips = std::uint32_t((views + targets - 1) / targets);
    return layout;
}

std::vector<render::Camera> stripCameras(std::span<const glm::mat4> cameraToWorld,
                                         std::uint32_t first,
                                         const StripLayout& layout,
                                         const glm::mat4& normalization,
                                         float horizontalFovRadians) {
    const float aspect = float(layout.width) / float(layout.height);
    const std::size_t last = cameraToWorld.size() - 1;
    std::vector<render::Camera> cameras;
    for (std::uint32_t strip = 0; strip < layout.strips; ++strip) {
        const std::size_t view = std::min<std::size_t>(first + strip, last);
        cameras.push_back(
            renderCamera(cameraToWorld[view], normalization, horizontalFovRadians, aspect));
    }
    return cameras;
}

image::ImageRgba8 cropStrip(const image::ImageRgba8& wide,
                            std::uint32_t strip,
                            std::uint32_t width) {
    image::ImageRgba8 view;
    view.width = width;
    view.height = wide.height;
    view.pixels.resize(std::size_t(width) * wide.height * 4);
    for (std::uint32_t y = 0; y < wide.height; ++y) {
        std::memcpy(&view.pixels[std::size_t(y) * width * 4], wide.pixel(strip * width, y),
                    std::size_t(width) * 4);
    }
    return view;
}

Result<std::vector<image::ImageRgba8>> renderStrips(render::Renderer& renderer,
                                                    const scene::Bounds& bounds,
                                                    std::span<const glm::mat4> cameraToWorld,
                                                    const ViewRigOptions& rig,
                                                    const StripLayout& layout) {
    const glm::mat4 toUnitBox = normalization(bounds, rig.normalize);
    const float fov = glm::radians(rig.horizontalFovDegrees);
    std::vector<image::ImageRgba8> views;
    for (std::uint32_t first = 0; first < cameraToWorld.size(); first += layout.strips) {
        renderer.renderViews(stripCameras(cameraToWorld, first, layout, toUnitBox, fov));
        auto wide = renderer.readImage();
        if (!wide) {
            return wide.error();
        }
        const std::uint32_t count =
            std::min<std::uint32_t>(layout.strips, std::uint32_t(cameraToWorld.size()) - first);
        for (std::uint32_t strip = 0; strip < count; ++strip) {
            views.push_back(cropStrip(*wide, strip, layout.width));
        }
    }
    return views;
}

}  // namespace encore::batch
