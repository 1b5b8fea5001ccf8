#include "encore/render/RenderTarget.h"

#include <string>

namespace encore::render {

namespace {
constexpr std::uint32_t kMaxTargetDimension = 8192;  // WebGPU's default maxTextureDimension2D.
}

Result<RenderTarget> RenderTarget::create(const wgpu::Device& device,
                                          const RenderTargetOptions& options) {
    if (options.width == 0 || options.height == 0 || options.width > kMaxTargetDimension ||
        options.height > kMaxTargetDimension) {
        return makeError(ErrorCode::InvalidArgument, "Image size " + std::to_string(options.width) +
                                                         "x" + std::to_string(options.height) +
                                                         " is outside 1.." +
                                                         std::to_string(kMaxTargetDimension) + ".");
    }
    if (options.sampleCount != 1 && options.sampleCount != 4) {
        return makeError(ErrorCode::InvalidArgument,
                         "Sample count " + std::to_string(options.sampleCount) +
                             " is not supported (WebGPU allows 1 or 4).");
    }
    RenderTarget target;
    target.mOptions = options;

    // The output holds RGBA8 bytes (kBytesFormat) that passes draw through an sRGB view
    // (kColorFormat): an sRGB format cannot be a storage texture, which strategies composing the
    // frame in compute write (FramePasses::composeFrame, through sceneStorageView(): on the H100 a
    // copy from a buffer into the texture took 0.044 ms of a 1280x720 frame).
    wgpu::TextureDescriptor output{};
    output.label = "render target output";
    output.size = {options.width, options.height, 1};
    output.format = kBytesFormat;
    // TextureBinding: the transmission pass copies the scene colour from it (without HDR).
    output.usage = wgpu::TextureUsage::RenderAttachment | wgpu::TextureUsage::CopySrc |
                   wgpu::TextureUsage::TextureBinding | wgpu::TextureUsage::CopyDst |
                   wgpu::TextureUsage::StorageBinding;
    output.viewFormatCount = 1;
    output.viewFormats = &kColorFormat;
    target.mOutput = device.CreateTexture(&output);
    wgpu::TextureViewDescriptor srgb{};
    srgb.label = "render target output";
    srgb.format = kColorFormat;
    srgb.usage = output.usage & ~wgpu::TextureUsage::StorageBinding;  // Not for sRGB formats.
    target.mOutputView = target.mOutput.CreateView(&srgb);
    wgpu::TextureViewDescriptor bytes{};
    bytes.label = "render target output bytes";
    bytes.format = kBytesFormat;
    target.mOutputBytesView = target.mOutput.CreateView(&bytes);
    if (options.hdr) {
        wgpu::TextureDescriptor scene = output;
        scene.label = "render target scene colour (HDR)";
        scene.format = kHdrFormat;
        scene.viewFormatCount = 0;
        scene.viewFormats = nullptr;
        scene.usage = wgpu::TextureUsage::RenderAttachment | wgpu::TextureUsage::TextureBinding |
                      wgpu::TextureUsage::CopySrc | wgpu::TextureUsage::CopyDst |
                      wgpu::TextureUsage::StorageBinding;
        target.mScene = device.CreateTexture(&scene);
        target.mSceneView = target.mScene.CreateView();
        target.mSceneStorageView = target.mSceneView;
    } else {
        target.mScene = target.mOutput;
        target.mSceneView = target.mOutputView;
        target.mSceneStorageView = target.mOutputBytesView;
    }

    if (options.sampleCount > 1) {
        wgpu::TextureDescriptor multisampled{};
        multisampled.label = "render target scene colour (multisampled)";
        multisampled.size = {options.width, options.height, 1};
        multisampled.format = target.sceneFormat();
        multisampled.sampleCount = options.sampleCount;
        multisampled.usage = wgpu::TextureUsage::RenderAttachment;
        if (options.exactIds && options.hdr) {
            multisampled.usage |= wgpu::TextureUsage::TextureBinding;  // SampleIdPass reads it.
        }
        target.mMultisampledScene = device.CreateTexture(&multisampled);
        target.mMultisampledSceneView = target.mMultisampledScene.CreateView();
    }

    wgpu::TextureDescriptor depth{};
    depth.label = "render target depth";
    depth.size = {options.width, options.height, 1};
    depth.format = kDepthFormat;
    depth.sampleCount = options.sampleCount;
    // Sampled by the depth pyramid of occlusion culling (DepthPyramid).
    depth.usage = wgpu::TextureUsage::RenderAttachment | wgpu::TextureUsage::TextureBinding;
    target.mDepth = device.CreateTexture(&depth);
    target.mDepthView = target.mDepth.CreateView();
    return target;
}

wgpu::RenderPassColorAttachment RenderTarget::colorAttachment(const wgpu::Color& clearColor) const {
    wgpu::RenderPassColorAttachment attachment{};
    if (mMultisampledScene) {
        attachment.view = mMultisampledSceneView;
        attachment.resolveTarget = mSceneView;
        attachment.storeOp = wgpu::StoreOp::Discard;
    } else {
        attachment.view = mSceneView;
        attachment.storeOp = wgpu::StoreOp::Store;
    }
    attachment.loadOp = wgpu::LoadOp::Clear;
    attachment.clearValue = clearColor;
    return attachment;
}

wgpu::RenderPassColorAttachment RenderTarget::resolvedColorAttachment(
    const wgpu::Color& clearColor) const {
    wgpu::RenderPassColorAttachment attachment{};
    attachment.view = mSceneView;
    attachment.storeOp = wgpu::StoreOp::Store;
    attachment.loadOp = wgpu::LoadOp::Clear;
    attachment.clearValue = clearColor;
    return attachment;
}

wgpu::RenderPassDepthStencilAttachment RenderTarget::depthAttachment() const {
    wgpu::RenderPassDepthStencilAttachment attachment{};
    attachment.view = mDepthView;
    attachment.depthLoadOp = wgpu::LoadOp::Clear;
    attachment.depthStoreOp = wgpu::StoreOp::Discard;
    attachment.depthClearValue = 1.0f;
    return attachment;
}

}  // namespace encore::render
