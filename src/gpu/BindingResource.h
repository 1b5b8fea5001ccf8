#pragma once

// Bind groups from a list of resources, in the spirit of Dawn's utils::MakeBindGroup: each
// BindingResource is a buffer range, a texture view or a sampler at a binding of the group's
// layout (gpu::LayoutEntry, LayoutEntry.h, describes the layout's side).
//
//     const wgpu::BindGroup group = gpu::makeBindGroup(
//         device, layout, {{0, uniformBuffer, 0, sizeof(Uniform)}, {1, view}, {2, sampler}},
//         "tone mapping");

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <initializer_list>
#include <span>

namespace encore::gpu {

struct BindingResource {
    // `size` bytes of `buffer` from `offset`; by default, all of it.
    BindingResource(std::uint32_t binding,
                    const wgpu::Buffer& buffer,
                    std::uint64_t offset = 0,
                    std::uint64_t size = wgpu::kWholeSize);
    BindingResource(std::uint32_t binding, const wgpu::TextureView& view);
    BindingResource(std::uint32_t binding, const wgpu::Sampler& sampler);

    wgpu::BindGroupEntry resource{};
};

// A bind group of `layout` (a layout made with makeBindGroupLayout, or a pipeline's
// GetBindGroupLayout) binding `resources`. Like any creation, an invalid one raises a
// validation error (gpu::Context::checkNoErrors) and returns an error object.
wgpu::BindGroup makeBindGroup(const wgpu::Device& device,
                              const wgpu::BindGroupLayout& layout,
                              std::span<const BindingResource> resources,
                              wgpu::StringView label = {});
wgpu::BindGroup makeBindGroup(const wgpu::Device& device,
                              const wgpu::BindGroupLayout& layout,
                              std::initializer_list<BindingResource> resources,
                              wgpu::StringView label = {});

}  // namespace encore::gpu
