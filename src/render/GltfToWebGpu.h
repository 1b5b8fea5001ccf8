#pragma once

// Every glTF -> WebGPU mapping in one place: vertex formats, topologies, index formats, sampler
// modes. src/scene guarantees the inputs are WebGPU-legal; these functions only translate.

#include <webgpu/webgpu_cpp.h>

#include <optional>

#include "encore/scene/SceneData.h"

namespace encore::render {

// The vertex format of an attribute accessor, or nullopt when WebGPU has none (the loader
// repacks such accessors, so a nullopt here is a bug).
std::optional<wgpu::VertexFormat> vertexFormat(const scene::Accessor& accessor);

wgpu::PrimitiveTopology primitiveTopology(scene::Topology topology);
bool isStrip(scene::Topology topology);

// Uint16 or Uint32 index accessors.
wgpu::IndexFormat indexFormat(const scene::Accessor& accessor);

// Shader location of a semantic, or nullopt when no shader consumes it.
std::optional<std::uint32_t> shaderLocation(scene::Semantic semantic);

wgpu::FilterMode filterMode(scene::Filter filter);
wgpu::MipmapFilterMode mipmapFilterMode(scene::Filter filter);
wgpu::AddressMode addressMode(scene::Wrap wrap);

}  // namespace encore::render
