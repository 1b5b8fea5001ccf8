#pragma once

// The passes of a view read back as HDR floats (Renderer::readHdrImage: RGBA, the target's
// width, premultiplied by coverage) and what the batch makes of them: EXR depth in the units of
// transforms.json, HDR radiance, segmentation ids (docs/batch.md#passes). The 8-bit passes
// (normal, albedo, material) go through the colour read-back instead (ViewStrips.h).

#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "encore/batch/ViewImages.h"
#include "encore/gpu/DeviceLimits.h"
#include "encore/image/ImageCodec.h"
#include "encore/render/Renderer.h"
#include "encore/scene/SceneData.h"
#include "gpu/TextureReadbackRing.h"
#include "render/Lighting.h"

namespace encore::batch {

// The debug channel that draws pass `kind` (Normal, Depth, Albedo, Material, Segmentation,
// Coordinates: the position); Shaded for the colour and HDR images, which come from the shaded
// frame.
render::DebugChannel passChannel(ViewImage kind, SegmentationBy by);
// The same as `images` asks for the pass: the geometric normal's channel for
// NormalKind::Geometric, segmentation by images.segmentationBy.
render::DebugChannel passChannel(ViewImage kind, const ExtraImages& images);

// Where strip `strip` of a wide float read-back lies.
struct FloatStrip {
    std::span<const float> wide;
    std::uint32_t targetWidth = 0;
    std::uint32_t strip = 0;
    std::uint32_t width = 0;
    std::uint32_t height = 0;

    const float* texel(std::uint32_t x, std::uint32_t y) const {
        return &wide[(std::size_t(y) * targetWidth + std::size_t(strip) * width + x) * 4];
    }
};

// A strip of three values per texel drawn over an empty background (so that edges hold the
// covered samples' values times their coverage, in alpha): `map(texel, coverage)` turns each
// texel with some coverage into the value to keep, or none to leave it empty; kept texels get
// the coverage (at most 1) as alpha, the others 0 in every channel.
template <typename Map>
std::vector<float> coveredTexels(const FloatStrip& strip, Map&& map) {
    std::vector<float> values(std::size_t(strip.width) * strip.height * 4, 0.0f);
    for (std::uint32_t y = 0; y < strip.height; ++y) {
        for (std::uint32_t x = 0; x < strip.width; ++x) {
            const float* texel = strip.texel(x, y);
            const float coverage = texel[3];
            if (!(coverage > 0.0f)) {
                continue;
            }
            const std::optional<glm::vec3> value = map(texel, coverage);
            if (!value) {
                continue;
            }
            float* out = &values[(std::size_t(y) * strip.width + x) * 4];
            out[0] = value->x;
            out[1] = value->y;
            out[2] = value->z;
            out[3] = std::min(coverage, 1.0f);
        }
    }
    return values;
}

// A strip drawn through the depth channel as distances along the camera axis in the units of
// the cameras (the scene scaled by `unitsPerModelUnit`, the normalisation's scale), infinity
// where less than half of the pixel is covered: the EXR depth.
std::vector<float> depthDistances(const FloatStrip& strip, float unitsPerModelUnit);

// A strip of the shaded frame's linear colour, RGBA premultiplied (as EXR stores it).
std::vector<float> hdrPixels(const FloatStrip& strip);

// A strip drawn through a segmentation channel: its ids, 0 where less than half of the pixel is
// covered (the channel writes R = id % 256, G = id / 256, times coverage).
image::ImageGray16 segmentationIds(const FloatStrip& strip);

// The same from a pass target that holds depth, id % 256, id / 256 and coverage
// (render::PassImage::DepthAndId): the same values, one channel further on.
image::ImageGray16 segmentationIdsOfPassTarget(const FloatStrip& strip);

// Strip `strip` (of `width` texels) of a ring read of half floats (bytesPerTexel 8) as RGBA
// floats, rows packed.
std::vector<float> halfStrip(const gpu::MappedReadback& wide,
                             std::uint32_t strip,
                             std::uint32_t width);

// Whether a batch draws its passes as pass targets of the colour frame (one render pass,
// render::RendererOptions::passTargets) rather than one frame per pass: when it has a pass
// other than HDR, `drawing` is Targets, the strategy draws glTF materials in its mesh shader and
// the device has the colour attachment bytes, and normals are not asked for in another
// convention (ExtraImages::normalsAsFloats).
bool drawsPassTargets(const ExtraImages& images,
                      render::StrategyKind strategy,
                      const gpu::DeviceLimits& limits);
// The renderer's pass targets for a segmentation by `by`.
render::PassTargets passTargetsFor(SegmentationBy by);
// The pass image that holds `kind` (Normal, Albedo, Material; Depth and Segmentation share
// DepthAndId).
render::PassImage passImageOf(ViewImage kind);
// How an image of `kind` is compressed when the batch asks for `chosen`: segmentation ids always
// Fast (flat regions of one id: runs are the matches there are, as small as Small in a ninth of
// the time, docs/benchmarks/2026-11-26-png-paeth-runs.md).
image::PngCompression pngCompressionOf(ViewImage kind, image::PngCompression chosen);

// What each id of a scene's segmentation names: id (1 + the index) and the node's, mesh's or
// material's name (empty when unnamed); nodes only where they draw a mesh.
struct SegmentationName {
    std::uint32_t id = 0;
    std::string name;
};
std::vector<SegmentationName> segmentationNames(const scene::SceneData& scene, SegmentationBy by);

}  // namespace encore::batch
