#pragma once

// Bind group layouts and pipeline layouts from a list of entries, in the spirit of Dawn's
// utils::MakeBindGroupLayout. A LayoutEntry says what a shader expects at one binding (a uniform
// buffer, a texture, a sampler...); the resources bound there are gpu::BindingResource
// (BindingResource.h). The two are distinct types so that one cannot be passed for the other.
//
//     const wgpu::BindGroupLayout layout = gpu::makeBindGroupLayout(
//         device, {gpu::LayoutEntry::uniform(0, wgpu::ShaderStage::Fragment, sizeof(Uniform)),
//                  gpu::LayoutEntry::texture(1, wgpu::ShaderStage::Fragment)},
//         "tone mapping");

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <initializer_list>
#include <span>

namespace encore::gpu {

// One entry of a bind group layout, made by the named constructors below. Unless a constructor
// says otherwise, its arguments are those of WebGPU's binding layouts with WebGPU's defaults.
struct LayoutEntry {
    // A buffer of `minBindingSize` bytes at least (0: checked at draw time, not at binding).
    static LayoutEntry uniform(std::uint32_t binding,
                               wgpu::ShaderStage visibility,
                               std::uint64_t minBindingSize = 0);
    static LayoutEntry storage(std::uint32_t binding,
                               wgpu::ShaderStage visibility,
                               std::uint64_t minBindingSize = 0);
    static LayoutEntry readOnlyStorage(std::uint32_t binding,
                                       wgpu::ShaderStage visibility,
                                       std::uint64_t minBindingSize = 0);
    // A sampled texture: Float by default, which needs a filterable format; UnfilterableFloat
    // accepts any float format but only textureLoad (or a NonFiltering sampler) reads it.
    static LayoutEntry texture(
        std::uint32_t binding,
        wgpu::ShaderStage visibility,
        wgpu::TextureSampleType sampleType = wgpu::TextureSampleType::Float,
        wgpu::TextureViewDimension viewDimension = wgpu::TextureViewDimension::e2D,
        bool multisampled = false);
    static LayoutEntry sampler(std::uint32_t binding,
                               wgpu::ShaderStage visibility,
                               wgpu::SamplerBindingType type = wgpu::SamplerBindingType::Filtering);
    static LayoutEntry storageTexture(
        std::uint32_t binding,
        wgpu::ShaderStage visibility,
        wgpu::TextureFormat format,
        wgpu::StorageTextureAccess access = wgpu::StorageTextureAccess::WriteOnly,
        wgpu::TextureViewDimension viewDimension = wgpu::TextureViewDimension::e2D);

    // The same buffer entry, its offset given to SetBindGroup as a dynamic offset instead of
    // fixed in the bind group.
    LayoutEntry withDynamicOffset() const;

    wgpu::BindGroupLayoutEntry entry{};
};

wgpu::BindGroupLayout makeBindGroupLayout(const wgpu::Device& device,
                                          std::span<const LayoutEntry> entries,
                                          wgpu::StringView label = {});
wgpu::BindGroupLayout makeBindGroupLayout(const wgpu::Device& device,
                                          std::initializer_list<LayoutEntry> entries,
                                          wgpu::StringView label = {});

// A pipeline layout of `groups`: bind group i of the pipeline has layout groups[i].
wgpu::PipelineLayout makePipelineLayout(const wgpu::Device& device,
                                        std::span<const wgpu::BindGroupLayout> groups,
                                        wgpu::StringView label = {});
wgpu::PipelineLayout makePipelineLayout(const wgpu::Device& device,
                                        std::initializer_list<wgpu::BindGroupLayout> groups,
                                        wgpu::StringView label = {});

}  // namespace encore::gpu
