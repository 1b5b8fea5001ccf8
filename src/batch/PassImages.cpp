#include "batch/PassImages.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace encore::batch {

render::DebugChannel passChannel(ViewImage kind, SegmentationBy by) {
    switch (kind) {
        case ViewImage::Normal:
            return render::DebugChannel::Normal;
        case ViewImage::Depth:
            return render::DebugChannel::Depth;
        case ViewImage::Albedo:
            return render::DebugChannel::BaseColor;
        case ViewImage::Material:
            return render::DebugChannel::Material;
        case ViewImage::Segmentation:
            return by == SegmentationBy::Mesh       ? render::DebugChannel::SegmentMesh
                   : by == SegmentationBy::Material ? render::DebugChannel::SegmentMaterial
                                                    : render::DebugChannel::SegmentNode;
        case ViewImage::Color:
        case ViewImage::Hdr:
            break;
    }
    return render::DebugChannel::Shaded;
}

std::vector<float> depthDistances(const FloatStrip& strip, float unitsPerModelUnit) {
    std::vector<float> depth(std::size_t(strip.width) * strip.height,
                             std::numeric_limits<float>::infinity());
    for (std::uint32_t y = 0; y < strip.height; ++y) {
        for (std::uint32_t x = 0; x < strip.width; ++x) {
            const float* texel = strip.texel(x, y);
            // Edges hold depth x coverage over an empty (0) background, as in depthStrip.
            const float coverage = texel[3];
            if (coverage >= 0.5f) {
                depth[std::size_t(y) * strip.width + x] = texel[0] / coverage * unitsPerModelUnit;
            }
        }
    }
    return depth;
}

std::vector<float> hdrPixels(const FloatStrip& strip) {
    std::vector<float> rgba(std::size_t(strip.width) * strip.height * 4);
    for (std::uint32_t y = 0; y < strip.height; ++y) {
        const float* row = strip.texel(0, y);
        std::copy(row, row + std::size_t(strip.width) * 4,
                  rgba.begin() + std::ptrdiff_t(std::size_t(y) * strip.width * 4));
    }
    return rgba;
}

image::ImageGray16 segmentationIds(const FloatStrip& strip) {
    image::ImageGray16 ids;
    ids.width = strip.width;
    ids.height = strip.height;
    ids.pixels.resize(std::size_t(strip.width) * strip.height);
    for (std::uint32_t y = 0; y < strip.height; ++y) {
        for (std::uint32_t x = 0; x < strip.width; ++x) {
            const float* texel = strip.texel(x, y);
            const float coverage = texel[3];
            if (!(coverage >= 0.5f)) {
                continue;
            }
            const long low = std::lround(texel[0] / coverage);
            const long high = std::lround(texel[1] / coverage);
            ids.pixels[std::size_t(y) * strip.width + x] =
                std::uint16_t(std::clamp(high * 256 + low, 0l, 65535l));
        }
    }
    return ids;
}

std::vector<SegmentationName> segmentationNames(const scene::SceneData& scene, SegmentationBy by) {
    std::vector<SegmentationName> names;
    switch (by) {
        case SegmentationBy::Node:
            for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
                if (scene.nodes[i].mesh) {
                    names.push_back({std::uint32_t(i + 1), scene.nodes[i].name});
                }
            }
            break;
        case SegmentationBy::Mesh:
            for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
                names.push_back({std::uint32_t(i + 1), scene.meshes[i].name});
            }
            break;
        case SegmentationBy::Material:
            for (std::size_t i = 0; i < scene.materials.size(); ++i) {
                names.push_back({std::uint32_t(i + 1), scene.materials[i].name});
            }
            break;
    }
    return names;
}

const char* segmentationByName(SegmentationBy by) {
    switch (by) {
        case SegmentationBy::Mesh:
            return "mesh";
        case SegmentationBy::Material:
            return "material";
        case SegmentationBy::Node:
            break;
    }
    return "node";
}

}  // namespace encore::batch
