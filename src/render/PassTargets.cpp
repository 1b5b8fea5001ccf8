#include "render/PassTargets.h"

namespace encore::render {

namespace {

constexpr const char* kTargetLabels[kPassTargetCount] = {
    "pass target normal", "pass target albedo", "pass target material", "pass target depth + id"};

}  // namespace

std::uint8_t passTargetsVariant(PassTargets targets) {
    return static_cast<std::uint8_t>(targets);
}

Result<PassTargetTextures> PassTargetTextures::create(const wgpu::Device& device,
                                                      const wgpu::Queue& queue,
                                                      shaders::ShaderLibrary& shaders,
                                                      const RenderTarget& target) {
    if (!target.hdr()) {
        return makeError(ErrorCode::InvalidArgument, "Pass targets need an HDR render target.");
    }
    PassTargetTextures textures;
    // Tone mapping off, straight alpha out: the debug channels' frames (drawDebugChannel).
    ToneMappingOptions identity;
    identity.toneMapping = ToneMapping::None;
    identity.exposure = 1.0f;
    identity.background = BackgroundKind::Transparent;
    const bool exactIds = target.options().exactIds && target.sampleCount() > 1;
    for (std::uint32_t i = 0; i < kPassTargetCount; ++i) {
        Target& pass = textures.mTargets[i];
        wgpu::TextureDescriptor resolved{};
        resolved.label = kTargetLabels[i];
        resolved.size = {target.width(), target.height(), 1};
        resolved.format = RenderTarget::kHdrFormat;
        resolved.usage = wgpu::TextureUsage::RenderAttachment | wgpu::TextureUsage::TextureBinding |
                         wgpu::TextureUsage::CopySrc;
        pass.resolved = device.CreateTexture(&resolved);
        pass.resolvedView = pass.resolved.CreateView();
        if (target.sampleCount() > 1) {
            wgpu::TextureDescriptor multisampled = resolved;
            multisampled.sampleCount = target.sampleCount();
            multisampled.usage = wgpu::TextureUsage::RenderAttachment;
            if (exactIds && i + 1 == kPassTargetCount) {
                multisampled.usage |= wgpu::TextureUsage::TextureBinding;  // SampleIdPass.
            }
            pass.multisampled = device.CreateTexture(&multisampled);
            pass.multisampledView = pass.multisampled.CreateView();
        }
        if (i + 1 == kPassTargetCount) {
            if (exactIds) {
                ENCORE_TRY_ASSIGN(auto ids,
                                  SampleIdPass::create(device, shaders, IdChannels::GreenBlue));
                ids.bindSource(device, pass.multisampledView);
                textures.mIds = std::move(ids);
            }
            break;  // Depth and ids are read back as they are.
        }
        wgpu::TextureDescriptor image = resolved;
        image.format = RenderTarget::kColorFormat;
        image.usage = wgpu::TextureUsage::RenderAttachment | wgpu::TextureUsage::CopySrc;
        constexpr wgpu::TextureFormat kBytesFormat = wgpu::TextureFormat::RGBA8Unorm;
        if (target.options().bytesViews) {
            image.usage |= wgpu::TextureUsage::TextureBinding;
            image.viewFormatCount = 1;
            image.viewFormats = &kBytesFormat;
        }
        pass.image = device.CreateTexture(&image);
        if (target.options().bytesViews) {
            wgpu::TextureViewDescriptor bytes{};
            bytes.label = "pass image bytes";
            bytes.format = kBytesFormat;
            pass.bytesView = pass.image.CreateView(&bytes);
        }
        pass.imageView = pass.image.CreateView();
        ENCORE_TRY_ASSIGN(auto converter,
                          ToneMapper::create(device, queue, shaders, target, identity));
        converter.bindSource(device, pass.resolvedView);
        textures.mConverters.push_back(std::move(converter));
    }
    return textures;
}

void PassTargetTextures::fillAttachments(
    const wgpu::RenderPassColorAttachment& color,
    std::span<wgpu::RenderPassColorAttachment, kPassTargetCount> attachments) const {
    for (std::size_t i = 0; i < kPassTargetCount; ++i) {
        const Target& pass = mTargets[i];
        wgpu::RenderPassColorAttachment& attachment = attachments[i];
        attachment = color;
        if (pass.multisampled) {
            attachment.view = pass.multisampledView;
            attachment.resolveTarget = color.resolveTarget ? pass.resolvedView : nullptr;
        } else {
            attachment.view = pass.resolvedView;
        }
        attachment.clearValue = {0.0, 0.0, 0.0, 0.0};
    }
    if (mIds) {
        // Whatever the pass resolves, encodeImages reads the samples after the last one.
        attachments[kPassTargetCount - 1].storeOp = wgpu::StoreOp::Store;
    }
}

void PassTargetTextures::encodeImages(const wgpu::CommandEncoder& commands) const {
    if (mIds) {
        mIds->encode(commands, mTargets[kPassTargetCount - 1].resolvedView);
    }
    for (std::size_t i = 0; i < mConverters.size(); ++i) {
        mConverters[i].encode(commands, mTargets[i].imageView);
    }
}

const wgpu::TextureView& PassTargetTextures::bytesView(PassImage image) const {
    const Target& pass = mTargets[static_cast<std::size_t>(image)];
    return image == PassImage::DepthAndId ? pass.resolvedView : pass.bytesView;
}

const wgpu::Texture& PassTargetTextures::texture(PassImage image) const {
    const Target& pass = mTargets[static_cast<std::size_t>(image)];
    return image == PassImage::DepthAndId ? pass.resolved : pass.image;
}

}  // namespace encore::render
