#include "render/GltfToWebGpu.h"

#include "shaders/VertexLocations.h"

namespace encore::render {

using scene::ComponentType;

std::optional<wgpu::VertexFormat> vertexFormat(const scene::Accessor& accessor) {
    using F = wgpu::VertexFormat;
    const int count = accessor.componentCount;
    const bool normalized = accessor.normalized;
    // WebGPU has 8- and 16-bit formats only with 2 or 4 components (the loader repacks others).
    auto pick = [&](F x2, F x4) -> std::optional<F> {
        if (count == 2) {
            return x2;
        }
        if (count == 4) {
            return x4;
        }
        return std::nullopt;
    };
    switch (accessor.componentType) {
        case ComponentType::Float32: {
            static constexpr F kFloat[] = {F::Float32, F::Float32x2, F::Float32x3, F::Float32x4};
            return count >= 1 && count <= 4 ? std::optional(kFloat[count - 1]) : std::nullopt;
        }
        case ComponentType::Uint32: {
            if (normalized) {
                return std::nullopt;
            }
            static constexpr F kUint[] = {F::Uint32, F::Uint32x2, F::Uint32x3, F::Uint32x4};
            return count >= 1 && count <= 4 ? std::optional(kUint[count - 1]) : std::nullopt;
        }
        case ComponentType::Uint8:
            return normalized ? pick(F::Unorm8x2, F::Unorm8x4) : pick(F::Uint8x2, F::Uint8x4);
        case ComponentType::Int8:
            return normalized ? pick(F::Snorm8x2, F::Snorm8x4) : pick(F::Sint8x2, F::Sint8x4);
        case ComponentType::Uint16:
            return normalized ? pick(F::Unorm16x2, F::Unorm16x4) : pick(F::Uint16x2, F::Uint16x4);
        case ComponentType::Int16:
            return normalized ? pick(F::Snorm16x2, F::Snorm16x4) : pick(F::Sint16x2, F::Sint16x4);
    }
    return std::nullopt;
}

wgpu::PrimitiveTopology primitiveTopology(scene::Topology topology) {
    switch (topology) {
        case scene::Topology::PointList:
            return wgpu::PrimitiveTopology::PointList;
        case scene::Topology::LineList:
            return wgpu::PrimitiveTopology::LineList;
        case scene::Topology::LineStrip:
            return wgpu::PrimitiveTopology::LineStrip;
        case scene::Topology::TriangleList:
            return wgpu::PrimitiveTopology::TriangleList;
        case scene::Topology::TriangleStrip:
            return wgpu::PrimitiveTopology::TriangleStrip;
    }
    return wgpu::PrimitiveTopology::TriangleList;
}

bool isStrip(scene::Topology topology) {
    return topology == scene::Topology::LineStrip || topology == scene::Topology::TriangleStrip;
}

wgpu::IndexFormat indexFormat(const scene::Accessor& accessor) {
    return accessor.componentType == ComponentType::Uint16 ? wgpu::IndexFormat::Uint16
                                                           : wgpu::IndexFormat::Uint32;
}

std::optional<std::uint32_t> shaderLocation(scene::Semantic semantic) {
    switch (semantic) {
        case scene::Semantic::Position:
            return shaders::kPositionLocation;
        case scene::Semantic::Normal:
            return shaders::kNormalLocation;
        case scene::Semantic::Texcoord0:
            return shaders::kTexcoord0Location;
        case scene::Semantic::Color0:
            return shaders::kColor0Location;
        case scene::Semantic::Tangent:
            return shaders::kTangentLocation;
        case scene::Semantic::Texcoord1:
            return shaders::kTexcoord1Location;
        case scene::Semantic::Joints0:
            return shaders::kJoints0Location;
        case scene::Semantic::Weights0:
            return shaders::kWeights0Location;
        case scene::Semantic::Joints1:
            return shaders::kJoints1Location;
        case scene::Semantic::Weights1:
            return shaders::kWeights1Location;
        default:
            return std::nullopt;
    }
}

wgpu::FilterMode filterMode(scene::Filter filter) {
    return filter == scene::Filter::Nearest ? wgpu::FilterMode::Nearest : wgpu::FilterMode::Linear;
}

wgpu::MipmapFilterMode mipmapFilterMode(scene::Filter filter) {
    return filter == scene::Filter::Nearest ? wgpu::MipmapFilterMode::Nearest
                                            : wgpu::MipmapFilterMode::Linear;
}

wgpu::AddressMode addressMode(scene::Wrap wrap) {
    switch (wrap) {
        case scene::Wrap::ClampToEdge:
            return wgpu::AddressMode::ClampToEdge;
        case scene::Wrap::MirroredRepeat:
            return wgpu::AddressMode::MirrorRepeat;
        case scene::Wrap::Repeat:
            return wgpu::AddressMode::Repeat;
    }
    return wgpu::AddressMode::Repeat;
}

}  // namespace encore::render
