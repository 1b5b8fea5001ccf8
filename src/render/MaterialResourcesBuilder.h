#pragma once

// MaterialResources::Builder: the texture and sampler upload behind MaterialResources::create
// and replaceBaseColorImage. It validates images and texture references, creates one texture
// per image and colour space (level 0 written through the queue or copied from a staged image,
// the mip chain recorded into `encoder`) and one sampler per distinct sampler state, and writes
// them into the MaterialResources under construction. Private to src/render.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "encore/core/Result.h"
#include "render/MaterialResources.h"

namespace encore::render {

// "Material 3 ('name')", the prefix of messages about a material.
std::string describeMaterial(scene::MaterialId id, const scene::Material& material);

// Creation state that the finished MaterialResources does not keep.
struct MaterialResources::Builder {
    const wgpu::Device& device;
    const wgpu::Queue& queue;
    const scene::SceneData& scene;
    MaterialResources& out;
    MipmapGenerator& mipmaps;
    wgpu::CommandEncoder encoder;
    StagedImages* staged = nullptr;
    gpu::ResourcePool* pool = nullptr;  // Where textures come from; null: created.
    std::uint32_t maxDimension = 8192;
    std::vector<wgpu::SamplerDescriptor> descriptors;  // Parallel to out.mSamplers, unlabelled.
    std::vector<scene::Sampler> states;  // Parallel to out.mSamplers: the first state of each.

    // Creates a texture with its full mip chain (levels past 0 left for the mip generator) and
    // writes level 0 from `pixels`, or copies it from `stagedPixels` when given.
    std::size_t addTexture(const std::string& label,
                           std::uint32_t width,
                           std::uint32_t height,
                           wgpu::TextureFormat format,
                           const std::uint8_t* pixels,
                           const wgpu::TexelCopyBufferInfo* stagedPixels = nullptr);

    // The texture of `image` in `space`, created on first use; kNone when the image has no
    // pixels (the loader already warned about it).
    Result<std::size_t> imageTexture(scene::ImageId id, ColorSpace space);

    // Validates and uploads one image with its mip chain; kNone when it has no pixels.
    Result<std::size_t> uploadImage(scene::ImageId id, const scene::Image& image, ColorSpace space);

    // The texture a texture reference binds, validating the reference on the way.
    Result<std::size_t> referencedTexture(scene::MaterialId materialId,
                                          const std::optional<scene::TextureRef>& ref,
                                          ColorSpace space);

    // One wgpu::Sampler per distinct state; scene samplers with equal state share it.
    std::size_t addSampler(const scene::Sampler& sampler, const std::string& label);
};

}  // namespace encore::render
