#pragma once

// What the passes that fill a texture's mip chain level by level share: MipmapGenerator (material
// textures) and TransmissionPass (the transmission background) both draw each level with
// mipmap.wgsl, a full-screen triangle sampling the level above through a bilinear,
// clamp-to-edge sampler. The same sampler, with linear mip filtering, samples the environment
// atlas (Environment).

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <vector>

namespace encore::render {

// floor(log2(max(width, height))) + 1: the level count of a full chain down to 1x1.
std::uint32_t fullMipLevelCount(std::uint32_t width, std::uint32_t height);

// Linear minification, magnification and mip filtering, clamped to the edge on every axis.
// Sampling a single-level view, as the mip passes do, the mip filter changes nothing.
wgpu::Sampler makeLinearClampSampler(const wgpu::Device& device, const char* label);

// mipmap.wgsl's group 0: the sampler at binding 0 and the source level at binding 1 (a filterable
// float texture), both for the fragment stage.
wgpu::BindGroupLayout makeMipSourceLayout(const wgpu::Device& device, const char* label);

// A 2D view of each mip level of `texture` (its first layer), level 0 first.
std::vector<wgpu::TextureView> mipLevelViews(const wgpu::Texture& texture);

}  // namespace encore::render
