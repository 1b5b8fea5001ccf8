#pragma once

// A model's views drawn side by side into one wide target (render::Renderer::renderViews), one
// strip per view: one frame and one read-back for many views. This says how many strips a
// target holds, which cameras fill them, and how the read-back image is cut into views.

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "batch/PassImages.h"
#include "encore/batch/ViewImages.h"
#include "encore/batch/ViewRig.h"
#include "encore/core/Result.h"
#include "encore/gpu/DeviceLimits.h"
#include "encore/image/ImageCodec.h"
#include "encore/render/Camera.h"
#include "encore/render/Renderer.h"

namespace encore::batch {

struct StripLayout {
    std::uint32_t width = 0;  // Of one view.
    std::uint32_t height = 0;
    std::uint32_t strips = 1;  // Views per target.

    std::uint32_t targetWidth() const { return width * strips; }
};

// As many strips as the device's texture width and buffer size allow for `views` views of
// width x height, spread evenly over the targets a model needs (12 views of 512 pixels: one
// target of 6144 x 512).
StripLayout stripLayout(std::uint32_t width,
                        std::uint32_t height,
                        std::uint32_t views,
                        const gpu::DeviceLimits& limits);

// The render cameras of views [first, first + layout.strips) of `views`, each with its own field
// of view; past the end the last view repeats, so that every strip keeps its width.
std::vector<render::Camera> stripCameras(std::span<const ViewCamera> views,
                                         std::uint32_t first,
                                         const StripLayout& layout,
                                         const glm::mat4& normalization);

// Strip `strip` of a read-back target image.
image::ImageRgba8 cropStrip(const image::ImageRgba8& wide,
                            std::uint32_t strip,
                            std::uint32_t width);
// The same from rows `bytesPerRow` apart (a mapped read-back buffer, gpu::MappedReadback).
image::ImageRgba8 cropStrip(const std::uint8_t* rows,
                            std::uint32_t bytesPerRow,
                            std::uint32_t height,
                            std::uint32_t strip,
                            std::uint32_t width);

// Normal and depth images (ViewImages.h) come from the renderer's debug channels, drawn with
// tone mapping off. What follows is shared by runBatch and renderStrips, so that both write the
// same values.

// Calls `draw` with `renderer` switched to `channel`, tone mapping off (identity, exposure 1)
// and a transparent background, then shades as before. Buffer writes only: recorded bundles
// stay valid. Fails, without drawing, when the target cannot take a transparent background.
// `rendererAlive`, when given, says after `draw` whether `renderer` still exists (a device loss
// inside `draw` may replace it); if not, nothing is switched back.
Result<void> drawDebugChannel(render::Renderer& renderer,
                              render::DebugChannel channel,
                              const std::function<void()>& draw,
                              const std::function<bool()>& rendererAlive = {});

// A normal image as read back: the target stores its colour sRGB-encoded, the image n * 0.5 +
// 0.5 linearly. Decoding the 8-bit values is exact to within one level (the HDR target holds the
// normal itself).
void decodeNormalImage(image::ImageRgba8& image);
// The table it decodes with: for each stored byte, the linear value's byte.
const std::array<std::uint8_t, 256>& srgbDecodedBytes();

// One step of a 16-bit depth image, in the units of the rig's cameras: the range covers twice
// the (largest) camera distance (transforms.json's depth_scale).
double depthScale(const ViewRigOptions& rig);
// Depth steps per unit of a depth target's depth (in model units before normalisation), as both
// depthStrip and the GPU's PNG rows (PngRowsPass) multiply by it, in floats: the same steps.
float depthStepsPerUnit(float unitsPerModelUnit, double scale);

// Strip `strip` of a target drawn through the depth channel and read back as HDR floats
// (Renderer::readHdrImage, RGBA, targetWidth wide): distances along the camera axis in steps of
// `scale`, the scene scaled by `unitsPerModelUnit` (the normalisation's scale), 0 where less
// than half of the pixel is covered.
image::ImageGray16 depthStrip(std::span<const float> wide,
                              std::uint32_t targetWidth,
                              std::uint32_t strip,
                              std::uint32_t width,
                              std::uint32_t height,
                              float unitsPerModelUnit,
                              double scale);

// Draws the views of the scene `renderer` has prepared (`views`, normalised by the scene's
// bounds as `rig` says) and reads them back, waiting for each target: for callers
// that render one model at a time (the Python module). `kind` is Color, Normal, Albedo or
// Material (the images `encore batch` writes as 000.png, 000_normal.png, ...). The renderer's
// target must be layout.targetWidth() x layout.height.
Result<std::vector<image::ImageRgba8>> renderStrips(render::Renderer& renderer,
                                                    const scene::Bounds& bounds,
                                                    std::span<const ViewCamera> views,
                                                    const ViewRigOptions& rig,
                                                    const StripLayout& layout,
                                                    ViewImage kind = ViewImage::Color);
// The same views' depth, as `encore batch --depth` writes it (000_depth.png, in steps of
// depthScale(rig)).
Result<std::vector<image::ImageGray16>> renderDepthStrips(render::Renderer& renderer,
                                                          const scene::Bounds& bounds,
                                                          std::span<const ViewCamera> views,
                                                          const ViewRigOptions& rig,
                                                          const StripLayout& layout);
// The same views' Hdr (RGBA linear colour, premultiplied) or Segmentation images (ids as floats,
// counting `by`), one vector of floats per view (PassImages.h). Depth: renderChannelStrips with
// depthOfKind.
Result<std::vector<std::vector<float>>> renderFloatStrips(render::Renderer& renderer,
                                                          const scene::Bounds& bounds,
                                                          std::span<const ViewCamera> views,
                                                          const ViewRigOptions& rig,
                                                          const StripLayout& layout,
                                                          ViewImage kind,
                                                          SegmentationBy by = SegmentationBy::Node);
// The same views drawn through `channel` and read back as floats (RGBA, premultiplied by
// coverage), each view's strip turned by `values(strip, view)` (`view` its index in `views`)
// into the floats kept for it: the passes whose values follow a convention (normals in another
// space, depth along rays, object coordinates) convert them with the batch's functions.
Result<std::vector<std::vector<float>>> renderChannelStrips(
    render::Renderer& renderer,
    const scene::Bounds& bounds,
    std::span<const ViewCamera> views,
    const ViewRigOptions& rig,
    const StripLayout& layout,
    render::DebugChannel channel,
    const std::function<std::vector<float>(const FloatStrip&, std::uint32_t)>& values);

}  // namespace encore::batch
