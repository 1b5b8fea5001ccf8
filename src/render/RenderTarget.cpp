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
        return makeError(ErrorCode::InvalidArgument,
                         "Image size " + std::to_string(options.width) + "x" +
                             std::to_string(options.height) + " is outside 1.." +
                             std::to_string(kMaxTargetDimension) + ".");
    }
    if (options.sampleCount != 1 && options.sampleCount != 4) {
        return makeError(ErrorCode::InvalidArgument,
                         "Sample count " + std::to_string(options.sampleCount) +
                             " is not supported (WebGPU allows 1 or 4).");
    }
    RenderTarget target;
    target.mOptions = options;

    wgpu::TextureDescriptor color{};
    color.label = "render target colour";
    color.size = {options.width, options.height, 1};
    color.format = kColorFormat;
    color.usage = wgpu::TextureUsage::RenderAttachment | wgpu::TextureUsage::CopySrc;
    target.mColor = device.CreateTexture(&color);
    target.mColorView = target.mColor.CreateView();

    if (options.sampleCount > 1) {
        wgpu::TextureDescriptor multisampled = color;
        multisampled.label = "render target colour (multisampled)";
        multisampled.sampleCount = options.sampleCount;
        multisampled.usage = wgpu::TextureUsage::RenderAttachment;
        target.mMultisampledColor = device.CreateTexture(&multisampled);
        target.mMultisampledColorView = target.mMultisampledColor.CreateView();
    }

    wgpu::TextureDescriptor depth{};
    depth.label = "render target depth";
    depth.size = {options.width, options.height, 1};
    depth.format = kDepthFormat;
    depth.sampleCount = options.sampleCount;
    depth.usage = wgpu::TextureUsage::RenderAttachment;
    target.mDepth = device.CreateTexture(&depth);
    target.mDepthView = target.mDepth.CreateView();
    return target;
}

wgpu::RenderPassColorAttachment RenderTarget::colorAttachment(const wgpu::Color& clearColor) const {
    wgpu::RenderPassColorAttachment attachment{};
    if (mMultisampledColor) {
        attachment.view = mMultisampledColorView;
        attachment.resolveTarget = mColorView;
        attachment.storeOp = wgpu::StoreOp::Discard;
    } else {
        attachment.view = mColorView;
        attachment.storeOp = wgpu::StoreOp::Store;
    }
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
