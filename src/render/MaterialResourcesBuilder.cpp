#include "render/MaterialResourcesBuilder.h"

#include <chrono>
#include <string>
#include <utility>

#include "core/Elapsed.h"
#include "gpu/ResourcePool.h"
#include "render/FittedImage.h"
#include "render/GltfToWebGpu.h"
#include "render/MipmapGenerator.h"
#include "render/StagedImages.h"

namespace encore::render {

namespace {

// RenderAttachment for the mip generator's passes; CopySrc so tests and tools can read any
// level back (it costs nothing on the drivers Encore targets).
constexpr wgpu::TextureUsage kTextureUsage =
    wgpu::TextureUsage::TextureBinding | wgpu::TextureUsage::CopyDst |
    wgpu::TextureUsage::RenderAttachment | wgpu::TextureUsage::CopySrc;

std::string describeImage(scene::ImageId id, const scene::Image& image) {
    if (!id.valid()) {
        return "Image '" + image.name + "'";  // A replacement, not one of the scene's images.
    }
    return "Image " + std::to_string(id.value) + " ('" + image.name + "')";
}

wgpu::SamplerDescriptor samplerDescriptor(const scene::Sampler& sampler) {
    wgpu::SamplerDescriptor descriptor{};
    descriptor.addressModeU = addressMode(sampler.wrapS);
    descriptor.addressModeV = addressMode(sampler.wrapT);
    descriptor.addressModeW = wgpu::AddressMode::Repeat;
    descriptor.magFilter = filterMode(sampler.magFilter);
    descriptor.minFilter = filterMode(sampler.minFilter);
    descriptor.mipmapFilter = mipmapFilterMode(sampler.mipmapFilter);
    if (!sampler.useMipmaps) {
        // glTF's minFilter NEAREST/LINEAR means "no mipmaps": pin sampling to level 0.
        descriptor.mipmapFilter = wgpu::MipmapFilterMode::Nearest;
        descriptor.lodMaxClamp = 0.0f;
    }
    descriptor.maxAnisotropy = 1;
    return descriptor;
}

bool sameSampler(const wgpu::SamplerDescriptor& a, const wgpu::SamplerDescriptor& b) {
    return a.addressModeU == b.addressModeU && a.addressModeV == b.addressModeV &&
           a.magFilter == b.magFilter && a.minFilter == b.minFilter &&
           a.mipmapFilter == b.mipmapFilter && a.lodMaxClamp == b.lodMaxClamp;
}

}  // namespace

std::string describeMaterial(scene::MaterialId id, const scene::Material& material) {
    return "Material " + std::to_string(id.value) + " ('" + material.name + "')";
}

std::size_t MaterialResources::Builder::addTexture(const std::string& label,
                                                   std::uint32_t width,
                                                   std::uint32_t height,
                                                   wgpu::TextureFormat format,
                                                   const std::uint8_t* pixels,
                                                   const wgpu::TexelCopyBufferInfo* stagedPixels) {
    wgpu::TextureDescriptor descriptor{};
    descriptor.label = label.c_str();
    descriptor.usage = kTextureUsage;
    descriptor.dimension = wgpu::TextureDimension::e2D;
    descriptor.size = {width, height, 1};
    descriptor.format = format;
    descriptor.mipLevelCount = fullMipLevelCount(width, height);
    auto start = std::chrono::steady_clock::now();
    wgpu::Texture texture = pool ? pool->texture(descriptor) : device.CreateTexture(&descriptor);
    out.mUploadTimes.creation += millisecondsSince(start);
    start = std::chrono::steady_clock::now();

    wgpu::TexelCopyTextureInfo destination{};
    destination.texture = texture;
    wgpu::TexelCopyBufferLayout layout{};
    layout.bytesPerRow = width * 4;
    layout.rowsPerImage = height;
    const wgpu::Extent3D extent{width, height, 1};
    if (stagedPixels) {
        // Before the mip passes that read it, in the same command buffer.
        encoder.CopyBufferToTexture(stagedPixels, &destination, &extent);
    } else {
        queue.WriteTexture(&destination, pixels, std::size_t(width) * height * 4, &layout, &extent);
    }
    out.mUploadTimes.writes += millisecondsSince(start);
    out.mUploadedBytes += std::uint64_t(width) * height * 4;
    out.mTextures.push_back(std::move(texture));
    return out.mTextures.size() - 1;
}

Result<std::size_t> MaterialResources::Builder::imageTexture(scene::ImageId id, ColorSpace space) {
    if (!id.valid()) {
        return kNone;
    }
    if (id.index() >= scene.images.size()) {
        return makeError(ErrorCode::InvalidArgument,
                         "Image " + std::to_string(id.value) + " does not exist (the scene has " +
                             std::to_string(scene.images.size()) + " images).");
    }
    ImageTextures& textures = out.mImageTextures[id.index()];
    std::size_t& slot = space == ColorSpace::Srgb ? textures.srgb : textures.linear;
    if (slot != kNone) {
        return slot;
    }
    auto uploaded = uploadImage(id, scene.images[id.index()], space);
    if (uploaded) {
        slot = *uploaded;
    }
    return uploaded;
}

Result<std::size_t> MaterialResources::Builder::uploadImage(scene::ImageId id,
                                                            const scene::Image& image,
                                                            ColorSpace space) {
    if (image.rgba8.empty() || image.width == 0 || image.height == 0) {
        return kNone;
    }
    const std::uint64_t expected = std::uint64_t(image.width) * image.height * 4;
    if (image.rgba8.size() != expected) {
        return makeError(ErrorCode::InvalidArgument,
                         describeImage(id, image) + " has " + std::to_string(image.rgba8.size()) +
                             " bytes of pixels (" + std::to_string(image.width) + "x" +
                             std::to_string(image.height) + " RGBA8 needs " +
                             std::to_string(expected) + ").");
    }
    const bool srgb = space == ColorSpace::Srgb;
    const FittedImage fitted = fitImage(describeImage(id, image), image, srgb, maxDimension);
    // Staged images hold the original pixels: a downscaled one is written instead.
    const auto waitStart = std::chrono::steady_clock::now();
    const std::optional<wgpu::TexelCopyBufferInfo> stagedPixels =
        staged && fitted.downscaled.empty() ? staged->copySource(id) : std::nullopt;
    out.mUploadTimes.writes += millisecondsSince(waitStart);
    const std::size_t index = addTexture(
        image.name + (srgb ? " (sRGB)" : " (linear)"), fitted.size.width, fitted.size.height,
        srgb ? wgpu::TextureFormat::RGBA8UnormSrgb : wgpu::TextureFormat::RGBA8Unorm,
        fitted.pixels(), stagedPixels ? &*stagedPixels : nullptr);
    const auto start = std::chrono::steady_clock::now();
    ENCORE_TRY(mipmaps.generate(encoder, out.mTextures[index]));
    out.mUploadTimes.mipmaps += millisecondsSince(start);
    return index;
}

Result<std::size_t> MaterialResources::Builder::referencedTexture(
    scene::MaterialId materialId,
    const std::optional<scene::TextureRef>& ref,
    ColorSpace space) {
    if (!ref) {
        return kNone;
    }
    if (ref->texture.index() >= scene.textures.size()) {
        return makeError(ErrorCode::InvalidArgument,
                         describeMaterial(materialId, scene.materials[materialId.index()]) +
                             " references texture " + std::to_string(ref->texture.value) +
                             ", but the scene has " + std::to_string(scene.textures.size()) +
                             " textures.");
    }
    auto texture = imageTexture(scene.textures[ref->texture.index()].image, space);
    if (!texture) {
        return texture.error().withContext(
            describeMaterial(materialId, scene.materials[materialId.index()]));
    }
    return texture;
}

std::size_t MaterialResources::Builder::addSampler(const scene::Sampler& sampler,
                                                   const std::string& label) {
    const wgpu::SamplerDescriptor wanted = samplerDescriptor(sampler);
    for (std::size_t i = 0; i < descriptors.size(); ++i) {
        if (sameSampler(descriptors[i], wanted)) {
            return i;
        }
    }
    wgpu::SamplerDescriptor labelled = wanted;
    labelled.label = label.c_str();
    out.mSamplers.push_back(device.CreateSampler(&labelled));
    descriptors.push_back(wanted);
    states.push_back(sampler);
    return out.mSamplers.size() - 1;
}

}  // namespace encore::render
