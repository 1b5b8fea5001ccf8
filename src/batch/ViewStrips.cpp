#include "batch/ViewStrips.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "batch/PassImages.h"
#include "core/Bytes.h"
#include "image/Srgb.h"

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

std::vector<render::Camera> stripCameras(std::span<const ViewCamera> views,
                                         std::uint32_t first,
                                         const StripLayout& layout,
                                         const glm::mat4& normalization) {
    const float aspect = float(layout.width) / float(layout.height);
    const std::size_t last = views.size() - 1;
    std::vector<render::Camera> cameras;
    for (std::uint32_t strip = 0; strip < layout.strips; ++strip) {
        const ViewCamera& view = views[std::min<std::size_t>(first + strip, last)];
        cameras.push_back(renderCamera(view, normalization, aspect));
    }
    return cameras;
}

image::ImageRgba8 cropStrip(const image::ImageRgba8& wide,
                            std::uint32_t strip,
                            std::uint32_t width) {
    return cropStrip(wide.pixels.data(), wide.width * 4, wide.height, strip, width);
}

image::ImageRgba8 cropStrip(const std::uint8_t* rows,
                            std::uint32_t bytesPerRow,
                            std::uint32_t height,
                            std::uint32_t strip,
                            std::uint32_t width) {
    image::ImageRgba8 view;
    view.width = width;
    view.height = height;
    view.pixels.resize(std::size_t(width) * height * 4);
    for (std::uint32_t y = 0; y < height; ++y) {
        // A strip of width 0 has no pixels: view.pixels.data() is null.
        copyBytes(view.pixels.data() + std::size_t(y) * width * 4,
                  rows + std::size_t(y) * bytesPerRow + std::size_t(strip) * width * 4,
                  std::size_t(width) * 4);
    }
    return view;
}

Result<void> drawDebugChannel(render::Renderer& renderer,
                              render::DebugChannel channel,
                              const std::function<void()>& draw,
                              const std::function<bool()>& rendererAlive) {
    const render::LightingParameters shaded = renderer.lighting();
    const render::ToneMappingOptions mapped = renderer.toneMapping();
    render::LightingParameters debug = shaded;
    debug.debugChannel = channel;
    render::ToneMappingOptions identity = mapped;
    identity.toneMapping = render::ToneMapping::None;
    identity.exposure = 1.0f;
    identity.background = render::BackgroundKind::Transparent;
    renderer.setLighting(debug);
    Result<void> set = renderer.setToneMapping(identity);
    if (set) {
        draw();
    }
    if (rendererAlive && !rendererAlive()) {
        return set;
    }
    renderer.setLighting(shaded);
    (void)renderer.setToneMapping(mapped);  // Accepted before: cannot fail.
    return set;
}

const std::array<std::uint8_t, 256>& srgbDecodedBytes() {
    static const std::array<std::uint8_t, 256> kLinear = [] {
        std::array<std::uint8_t, 256> table{};
        for (int value = 0; value < 256; ++value) {
            table[value] = std::uint8_t(std::lround(image::srgbToLinear(value / 255.0) * 255.0));
        }
        return table;
    }();
    return kLinear;
}

void decodeNormalImage(image::ImageRgba8& image) {
    const std::array<std::uint8_t, 256>& linear = srgbDecodedBytes();
    for (std::size_t i = 0; i < image.pixels.size(); i += 4) {
        for (std::size_t channel = 0; channel < 3; ++channel) {
            image.pixels[i + channel] = linear[image.pixels[i + channel]];
        }
    }
}

double depthScale(const ViewRigOptions& rig) {
    return 2.0 * double(farthestDistance(rig)) / 65535.0;
}

float depthStepsPerUnit(float unitsPerModelUnit, double scale) {
    return float(double(unitsPerModelUnit) / scale);
}

image::ImageGray16 depthStrip(std::span<const float> wide,
                              std::uint32_t targetWidth,
                              std::uint32_t strip,
                              std::uint32_t width,
                              std::uint32_t height,
                              float unitsPerModelUnit,
                              double scale) {
    image::ImageGray16 depth;
    depth.width = width;
    depth.height = height;
    depth.pixels.resize(std::size_t(width) * height);
    const float stepsPerUnit = depthStepsPerUnit(unitsPerModelUnit, scale);
    for (std::uint32_t y = 0; y < height; ++y) {
        for (std::uint32_t x = 0; x < width; ++x) {
            const float* texel = &wide[(std::size_t(y) * targetWidth + strip * width + x) * 4];
            // Edges and blended surfaces hold depth x coverage over an empty (0) background;
            // below half coverage the quotient is mostly rounding (half floats): empty.
            const float coverage = texel[3];
            if (!(coverage >= 0.5f)) {
                continue;  // 0: nothing there.
            }
            // In floats, as png_rows.wgsl computes it on the GPU.
            const float steps = texel[0] / coverage * stepsPerUnit;
            depth.pixels[std::size_t(y) * width + x] =
                std::uint16_t(std::clamp(std::lround(steps), 1l, 65535l));
        }
    }
    return depth;
}

namespace {

// The per-target loop of the render*Strips: `drawTarget(cameras)` draws one target's views and
// reads it back (a Result of the wide image), `cutStrip(wide, strip, view)` makes the image of
// one of its strips, view `view` of `views`.
template <typename Image, typename DrawTarget, typename CutStrip>
Result<std::vector<Image>> renderTargets(const scene::Bounds& bounds,
                                         std::span<const ViewCamera> views,
                                         const ViewRigOptions& rig,
                                         const StripLayout& layout,
                                         DrawTarget drawTarget,
                                         CutStrip cutStrip) {
    const glm::mat4 toUnitBox = normalization(bounds, rig.normalize);
    std::vector<Image> images;
    for (std::uint32_t first = 0; first < views.size(); first += layout.strips) {
        const std::vector<render::Camera> cameras = stripCameras(views, first, layout, toUnitBox);
        ENCORE_TRY_ASSIGN(auto wide, drawTarget(std::span<const render::Camera>(cameras)));
        const std::uint32_t count =
            std::min<std::uint32_t>(layout.strips, std::uint32_t(views.size()) - first);
        for (std::uint32_t strip = 0; strip < count; ++strip) {
            images.push_back(cutStrip(wide, strip, first + strip));
        }
    }
    return images;
}

// Draws `cameras` through `channel` and reads the HDR target back: the floats of the passes that
// a debug channel draws (depth, segmentation, the conventions' normals and coordinates).
Result<std::vector<float>> drawChannelFloats(render::Renderer& renderer,
                                             render::DebugChannel channel,
                                             std::span<const render::Camera> cameras) {
    Result<std::vector<float>> wide = makeError(ErrorCode::InvalidArgument, "Not drawn.");
    ENCORE_TRY(drawDebugChannel(renderer, channel, [&] {
        renderer.renderViews(cameras);
        wide = renderer.readHdrImage();
    }));
    return wide;
}

}  // namespace

Result<std::vector<image::ImageRgba8>> renderStrips(render::Renderer& renderer,
                                                    const scene::Bounds& bounds,
                                                    std::span<const ViewCamera> views,
                                                    const ViewRigOptions& rig,
                                                    const StripLayout& layout,
                                                    ViewImage kind) {
    if (kind != ViewImage::Color && kind != ViewImage::Normal && kind != ViewImage::Albedo &&
        kind != ViewImage::Material) {
        return makeError(ErrorCode::InvalidArgument,
                         "Depth, segmentation and HDR images are not 8-bit RGBA: "
                         "renderDepthStrips and renderFloatStrips draw them.");
    }
    // Normals and material values are linear, stored sRGB-encoded by the output.
    const bool linear = kind == ViewImage::Normal || kind == ViewImage::Material;
    const auto drawTarget =
        [&](std::span<const render::Camera> cameras) -> Result<image::ImageRgba8> {
        Result<image::ImageRgba8> wide = makeError(ErrorCode::InvalidArgument, "Not drawn.");
        auto drawAndRead = [&] {
            renderer.renderViews(cameras);
            wide = renderer.readImage();
        };
        if (kind != ViewImage::Color) {
            ENCORE_TRY(
                drawDebugChannel(renderer, passChannel(kind, SegmentationBy::Node), drawAndRead));
        } else {
            drawAndRead();
        }
        return wide;
    };
    const auto cutStrip = [&](const image::ImageRgba8& wide, std::uint32_t strip, std::uint32_t) {
        image::ImageRgba8 view = cropStrip(wide, strip, layout.width);
        if (linear) {
            decodeNormalImage(view);
        }
        return view;
    };
    return renderTargets<image::ImageRgba8>(bounds, views, rig, layout, drawTarget, cutStrip);
}

Result<std::vector<std::vector<float>>> renderFloatStrips(render::Renderer& renderer,
                                                          const scene::Bounds& bounds,
                                                          std::span<const ViewCamera> views,
                                                          const ViewRigOptions& rig,
                                                          const StripLayout& layout,
                                                          ViewImage kind,
                                                          SegmentationBy by) {
    if (kind != ViewImage::Hdr && kind != ViewImage::Segmentation) {
        return makeError(ErrorCode::InvalidArgument,
                         "Only segmentation and HDR images are read back as floats here: "
                         "renderChannelStrips draws depth in its conventions.");
    }
    const auto drawTarget =
        [&](std::span<const render::Camera> cameras) -> Result<std::vector<float>> {
        if (kind != ViewImage::Hdr) {
            return drawChannelFloats(renderer, passChannel(kind, by), cameras);
        }
        renderer.renderViews(cameras);  // The shaded frame's linear colour.
        return renderer.readHdrImage();
    };
    const auto cutStrip = [&](const std::vector<float>& wide, std::uint32_t strip, std::uint32_t) {
        const FloatStrip pixels{wide, layout.targetWidth(), strip, layout.width, layout.height};
        if (kind == ViewImage::Hdr) {
            return hdrPixels(pixels);
        }
        const image::ImageGray16 ids = segmentationIds(pixels);
        return std::vector<float>(ids.pixels.begin(), ids.pixels.end());
    };
    return renderTargets<std::vector<float>>(bounds, views, rig, layout, drawTarget, cutStrip);
}

Result<std::vector<std::vector<float>>> renderChannelStrips(
    render::Renderer& renderer,
    const scene::Bounds& bounds,
    std::span<const ViewCamera> views,
    const ViewRigOptions& rig,
    const StripLayout& layout,
    render::DebugChannel channel,
    const std::function<std::vector<float>(const FloatStrip&, std::uint32_t)>& values) {
    const auto drawTarget = [&](std::span<const render::Camera> cameras) {
        return drawChannelFloats(renderer, channel, cameras);
    };
    const auto cutStrip = [&](const std::vector<float>& wide, std::uint32_t strip,
                              std::uint32_t view) {
        return values(FloatStrip{wide, layout.targetWidth(), strip, layout.width, layout.height},
                      view);
    };
    return renderTargets<std::vector<float>>(bounds, views, rig, layout, drawTarget, cutStrip);
}

Result<std::vector<image::ImageGray16>> renderDepthStrips(render::Renderer& renderer,
                                                          const scene::Bounds& bounds,
                                                          std::span<const ViewCamera> views,
                                                          const ViewRigOptions& rig,
                                                          const StripLayout& layout) {
    const auto drawTarget = [&](std::span<const render::Camera> cameras) {
        return drawChannelFloats(renderer, render::DebugChannel::Depth, cameras);
    };
    const float unitsPerModelUnit = normalization(bounds, rig.normalize)[0][0];
    const double scale = depthScale(rig);
    const auto cutStrip = [&](const std::vector<float>& wide, std::uint32_t strip, std::uint32_t) {
        return depthStrip(wide, layout.targetWidth(), strip, layout.width, layout.height,
                          unitsPerModelUnit, scale);
    };
    return renderTargets<image::ImageGray16>(bounds, views, rig, layout, drawTarget, cutStrip);
}

}  // namespace encore::batch
