#include "render/visibility/VisibilityTarget.h"

#include <algorithm>
#include <cstring>

#include "gpu/Upload.h"

namespace encore::render {

bool VisibilityTarget::ensure(const RenderSetup& setup,
                              std::uint32_t targetWidth,
                              std::uint32_t targetHeight,
                              std::size_t views,
                              std::uint32_t bins,
                              std::uint32_t maxGroups) {
    const wgpu::Device& device = setup.device;
    bool remade = false;
    if (views > viewCapacity) {
        viewCapacity = views;
        triangleCounts =
            gpu::createBuffer(device, wgpu::BufferUsage::CopyDst | wgpu::BufferUsage::CopySrc,
                              views * 8, "visibility triangle counts");
        remade = true;
    }
    const std::size_t slots = slotsFor(views, bins);
    if (slots > slotCapacity) {
        slotCapacity = slots;
        // The shading's binding of kSlotViews slots from any group's first view fits.
        params = gpu::createBuffer(device, wgpu::BufferUsage::Uniform | wgpu::BufferUsage::CopyDst,
                                   slots * kParamsStride + kSlotBindingBytes,
                                   "visibility view parameters");
        remade = true;
    }
    const std::uint32_t roundBins = std::clamp<std::uint32_t>(bins, 1, kRoundBins);
    const bool resized = targetWidth != width || targetHeight != height || !visibility;
    const std::uint64_t targetTiles = std::uint64_t(tilesFor(targetWidth)) * tilesFor(targetHeight);
    if (resized || roundBins > tileBins) {
        tileBins = std::max(roundBins, resized ? 0u : tileBins);
        tiles = gpu::createBuffer(device, wgpu::BufferUsage::Storage,
                                  std::max<std::uint64_t>(targetTiles * tileBins, 1) * 4,
                                  "visibility binned tiles");
        remade = true;
    }
    if (!resized) {
        return remade;
    }
    width = targetWidth;
    height = targetHeight;
    // An entry per sample: 8 bytes in the visibility buffer, a texel of the shaded colour (a
    // layer per sample, visibility_samples.wgsl).
    const std::uint32_t samples = setup.sampleCount;
    const std::uint64_t entries = std::uint64_t(width) * height * samples;
    shadeGroups = std::clamp<std::uint32_t>(
        std::uint32_t(std::min<std::uint64_t>(targetTiles, maxGroups)), 1, maxGroups);
    visibility = gpu::createBuffer(
        device,
        wgpu::BufferUsage::Storage | wgpu::BufferUsage::CopyDst | wgpu::BufferUsage::CopySrc,
        entries * 8, "visibility buffer");
    wgpu::TextureDescriptor texture{};
    texture.size = {width, height, samples};  // A layer per sample.
    texture.format = wgpu::TextureFormat::RGBA16Float;
    texture.usage = wgpu::TextureUsage::StorageBinding | wgpu::TextureUsage::TextureBinding |
                    wgpu::TextureUsage::CopySrc;  // For tests (VisibilityStrategy::shadedColour).
    texture.label = "visibility shaded colour";
    shaded = device.CreateTexture(&texture);
    wgpu::TextureViewDescriptor layers{};
    layers.dimension = wgpu::TextureViewDimension::e2DArray;  // Even with one layer.
    shadedLayers = shaded.CreateView(&layers);
    hardwareDepth = nullptr;  // Made at the views' size (ensureHardwareDepth).
    hardwareDepthView = nullptr;

    auto built =
        DepthPyramid::createFromVisibility(device, *setup.shaders, visibility, width, height);
    // The shader is embedded: a failure here is a bug, not an input error.
    ENCORE_CHECK(built.ok(), "the depth pyramid cannot be built: " + built.error().message);
    pyramid = std::move(*built);
    return true;
}

bool VisibilityTarget::ensureComposed(const RenderSetup& setup,
                                      const wgpu::TextureView& view,
                                      const wgpu::Color& background) {
    const bool changed = view.Get() != composedView.Get();
    composedView = view;
    if (!composition) {
        composition =
            gpu::createBuffer(setup.device, wgpu::BufferUsage::Uniform | wgpu::BufferUsage::CopyDst,
                              kCompositionBytes, "visibility composition");
    }
    // visibility_composed.wgsl's Composition: the background.
    std::array<std::uint32_t, kCompositionBytes / 4> words{};
    const std::array<float, 4> color = {float(background.r), float(background.g),
                                        float(background.b), float(background.a)};
    std::memcpy(words.data(), color.data(), sizeof(color));
    if (words != compositionWords) {
        setup.queue.WriteBuffer(composition, 0, words.data(), sizeof(words));
        compositionWords = words;
    }
    return changed;
}

void VisibilityTarget::ensureHardwareDepth(const RenderSetup& setup, std::uint32_t viewWidth) {
    if (hardwareDepth && hardwareDepth.GetWidth() == viewWidth &&
        hardwareDepth.GetHeight() == height) {
        return;
    }
    wgpu::TextureDescriptor texture{};
    texture.size = {std::max(viewWidth, 1u), std::max(height, 1u), 1};
    texture.format = wgpu::TextureFormat::Depth32Float;
    texture.usage = wgpu::TextureUsage::RenderAttachment;
    texture.sampleCount = setup.sampleCount;
    texture.label = "visibility hardware depth";
    hardwareDepth = setup.device.CreateTexture(&texture);
    hardwareDepthView = hardwareDepth.CreateView();
}

}  // namespace encore::render
