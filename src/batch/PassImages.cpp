#include "batch/PassImages.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "gpu/Readback.h"
#include "render/SceneColorTargets.h"

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
        case ViewImage::Coordinates:
            return render::DebugChannel::Position;
        case ViewImage::Color:
        case ViewImage::Hdr:
            break;
    }
    return render::DebugChannel::Shaded;
}

render::DebugChannel passChannel(ViewImage kind, const ExtraImages& images) {
    if (kind == ViewImage::Normal && images.normalKind == NormalKind::Geometric) {
        return render::DebugChannel::GeometricNormal;
    }
    return passChannel(kind, images.segmentationBy);
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

namespace {

// The ids of a strip whose texels hold id % 256 in `lowChannel`, id / 256 in the next and the
// coverage in the fourth, both ids times coverage.
image::ImageGray16 idsFromChannels(const FloatStrip& strip, std::size_t lowChannel) {
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
            const long low = std::lround(texel[lowChannel] / coverage);
            const long high = std::lround(texel[lowChannel + 1] / coverage);
            ids.pixels[std::size_t(y) * strip.width + x] =
                std::uint16_t(std::clamp(high * 256 + low, 0l, 65535l));
        }
    }
    return ids;
}

}  // namespace

image::ImageGray16 segmentationIds(const FloatStrip& strip) {
    return idsFromChannels(strip, 0);
}

image::ImageGray16 segmentationIdsOfPassTarget(const FloatStrip& strip) {
    return idsFromChannels(strip, 1);
}

std::vector<float> halfStrip(const gpu::MappedReadback& wide,
                             std::uint32_t strip,
                             std::uint32_t width) {
    // Every half's value, once: a lookup per texel channel (views of 512 x 512 have a million).
    static const std::vector<float> kHalves = [] {
        std::vector<float> values(65536);
        for (std::uint32_t half = 0; half < values.size(); ++half) {
            values[half] = gpu::halfToFloat(std::uint16_t(half));
        }
        return values;
    }();
    std::vector<float> texels(std::size_t(width) * wide.height * 4);
    for (std::uint32_t y = 0; y < wide.height; ++y) {
        const std::uint8_t* row =
            wide.rows + std::size_t(y) * wide.bytesPerRow + std::size_t(strip) * width * 8;
        float* out = &texels[std::size_t(y) * width * 4];
        for (std::size_t i = 0; i < std::size_t(width) * 4; ++i) {
            std::uint16_t half;
            std::memcpy(&half, row + i * 2, 2);
            out[i] = kHalves[half];
        }
    }
    return texels;
}

bool drawsPassTargets(const ExtraImages& images,
                      render::StrategyKind strategy,
                      const gpu::DeviceLimits& limits) {
    const bool passes =
        images.normals || images.depth || images.albedo || images.material || images.segmentation;
    const bool meshMaterials = strategy == render::StrategyKind::Materials ||
                               strategy == render::StrategyKind::Bundles ||
                               strategy == render::StrategyKind::GpuCulling ||
                               strategy == render::StrategyKind::GpuCullingBundles;
    // Normals in another convention and object coordinates are read as floats from a frame of
    // their own (the pass target's normal is converted to 8 bits on the GPU, and holds the
    // shading normal only; no target holds positions).
    return passes && !images.normalsAsFloats() && !images.coordinates &&
           images.drawing == PassDrawing::Targets && meshMaterials &&
           limits.maxColorAttachmentBytesPerSample >= render::kPassTargetBytesPerSample;
}

render::PassTargets passTargetsFor(SegmentationBy by) {
    switch (by) {
        case SegmentationBy::Mesh:
            return render::PassTargets::SegmentByMesh;
        case SegmentationBy::Material:
            return render::PassTargets::SegmentByMaterial;
        case SegmentationBy::Node:
            break;
    }
    return render::PassTargets::SegmentByNode;
}

render::PassImage passImageOf(ViewImage kind) {
    switch (kind) {
        case ViewImage::Normal:
            return render::PassImage::Normal;
        case ViewImage::Albedo:
            return render::PassImage::Albedo;
        case ViewImage::Material:
            return render::PassImage::Material;
        default:
            break;
    }
    return render::PassImage::DepthAndId;
}

image::PngCompression pngCompressionOf(ViewImage kind, image::PngCompression chosen) {
    return kind == ViewImage::Segmentation ? image::PngCompression::Fast : chosen;
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

}  // namespace encore::batch
