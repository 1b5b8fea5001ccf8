#pragma once

// A model's views drawn side by side into one wide target (render::Renderer::renderViews), one
// strip per view: one frame and one read-back for many views. This says how many strips a
// target holds, which cameras fill them, and how the read-back image is cut into views.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

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

// The render cameras of views [first, first + layout.strips) of `cameraToWorld`; past its end
// the last view repeats, so that every strip keeps its width.
std::vector<render::Camera> stripCameras(std::span<const glm::mat4> cameraToWorld,
                                         std::uint32_t first,
                                         const StripLayout& layout,
                                         const glm::mat4& normalization,
                                         float horizontalFovRadians);

// Strip `strip` of a read-back target image.
image::ImageRgba8 cropStrip(const image::ImageRgba8& wide,
                            std::uint32_t strip,
                            std::uint32_t width);

// Draws the views of the scene `renderer` has prepared (from `rig`'s cameras, normalised by
// the scene's bounds as `rig` says) and reads them back, waiting for each target: for callers
// that render one model at a time (the Python module). The renderer's target must be
// layout.targetWidth() x layout.height.
Result<std::vector<image::ImageRgba8>> renderStrips(render::Renderer& renderer,
                                                    const scene::Bounds& bounds,
                                                    std::span<const glm::mat4> cameraToWorld,
                                                    const ViewRigOptions& rig,
                                                    const StripLayout& layout);

}  // namespace encore::batch
