#include "batch/DepthConventions.h"

#include <algorithm>
#include <cmath>

#include "batch/TransformsJson.h"

namespace encore::batch {

double rayLengthPerDepth(const ViewCamera& view,
                         std::uint32_t width,
                         std::uint32_t height,
                         std::uint32_t x,
                         std::uint32_t y) {
    if (view.projection == Projection::Orthographic) {
        return 1.0;
    }
    // The intrinsics transforms.json records, so that its readers find the same rays.
    const PinholeIntrinsics intrinsics = intrinsicsFor(width, height, view.horizontalFovRadians);
    const double dx = (double(x) + 0.5 - intrinsics.centerX) / intrinsics.focalX;
    const double dy = (double(y) + 0.5 - intrinsics.centerY) / intrinsics.focalY;
    return std::sqrt(1.0 + dx * dx + dy * dy);
}

void depthAlongRays(std::span<float> depth,
                    const ViewCamera& view,
                    std::uint32_t width,
                    std::uint32_t height) {
    if (view.projection == Projection::Orthographic) {
        return;
    }
    for (std::uint32_t y = 0; y < height; ++y) {
        for (std::uint32_t x = 0; x < width; ++x) {
            float& value = depth[std::size_t(y) * width + x];
            value = float(double(value) * rayLengthPerDepth(view, width, height, x, y));
        }
    }
}

std::vector<float> depthOfKind(const FloatStrip& strip,
                               DepthKind kind,
                               float unitsPerModelUnit,
                               const ViewCamera& view) {
    std::vector<float> depth = depthDistances(strip, unitsPerModelUnit);
    if (kind == DepthKind::Ray) {
        depthAlongRays(depth, view, strip.width, strip.height);
    }
    return depth;
}

float depthUnitsPerModelUnit(DepthUnit unit, float unitsPerModelUnit) {
    return unit == DepthUnit::Model ? 1.0f : unitsPerModelUnit;
}

image::ImageGray16 depthStepsOf(std::span<const float> depth,
                                std::uint32_t width,
                                std::uint32_t height,
                                double scale) {
    image::ImageGray16 steps;
    steps.width = width;
    steps.height = height;
    steps.pixels.resize(std::size_t(width) * height);
    for (std::size_t i = 0; i < steps.pixels.size(); ++i) {
        if (std::isfinite(depth[i])) {
            steps.pixels[i] =
                std::uint16_t(std::clamp(std::lround(double(depth[i]) / scale), 1l, 65535l));
        }
    }
    return steps;
}

}  // namespace encore::batch
