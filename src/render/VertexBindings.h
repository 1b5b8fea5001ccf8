#pragma once

// The case study's Part 2 ("buffer layouts"), shared by every strategy after `naive`:
//  - the glTF bufferViews that primitives read, uploaded once into one GPU buffer (more only
//    past maxBufferSize), each view at a 4-byte-aligned offset and bound with its own size:
//    Dawn tracks every distinct buffer a pass uses (a hash-map entry and a barrier check per
//    buffer per frame, bundles included), so one buffer for all geometry keeps that cost flat;
//  - a primitive's attributes grouped per bufferView: attributes whose offsets lie within one
//    stride of each other are interleaved and bound once, as one vertex buffer slot; attributes
//    further apart (non-interleaved data sharing a view) get slots of their own;
//  - each slot's smallest attribute offset moves into the setVertexBuffer offset, so layouts
//    carry small offsets (models with accessor offsets past the stride or 2048 draw fine);
//  - attributes sorted by shader location and slots by their first location, so equal layouts
//    compare equal (what lets the pipeline cache share pipelines).
// Attributes that cannot be bound in place (an unaligned offset, a stride that is not a multiple
// of 4) are copied into a private, padded buffer instead.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "encore/core/Result.h"
#include "encore/scene/SceneData.h"
#include "render/PipelineKey.h"

namespace encore::gpu {
class ResourcePool;
}

namespace encore::render {

class StagedGeometry;

struct VertexBufferBinding {
    wgpu::Buffer buffer;
    std::uint64_t offset = 0;
    // The bytes the slot may read: up to the end of its bufferView, so a shared buffer binds no
    // more than a buffer of its own would.
    std::uint64_t size = wgpu::kWholeSize;
};

struct IndexBufferBinding {
    wgpu::Buffer buffer;
    wgpu::IndexFormat format = wgpu::IndexFormat::Undefined;
    std::uint64_t offset = 0;
    std::uint32_t count = 0;
    std::uint64_t size = wgpu::kWholeSize;
};

// How to bind one primitive: slots in order, the layout part of its pipeline key, the draw.
struct PrimitiveBindings {
    std::vector<VertexBufferBinding> vertexBuffers;  // Slot i.
    PipelineKey layout;  // bufferCount/buffers filled; other fields left default.
    std::optional<IndexBufferBinding> indices;
    std::uint32_t vertexCount = 0;
    scene::Topology topology = scene::Topology::TriangleList;
};

// Owns the GPU geometry of one scene (part of the GpuScene) and computes primitive bindings
// over it.
class GeometryBuffers {
  public:
    // Uploads the bufferViews that the scene's primitives read, and padded copies of the
    // attributes that cannot be bound in place (all of them now, not on first bind: every
    // strategy binds from the same uploads). `maxSharedBufferBytes`: where a
    // shared buffer ends and the next begins; 0 (the default) takes the device's maxBufferSize
    // (tests pass less to exercise the split). `staged`: the shared buffers' bytes already in
    // staging buffers (StagedGeometry.h), copied from there, used during this call only.
    // `pool`: where the shared buffers come from (gpu/ResourcePool.h). `uploads`: the encoder
    // the staged copies are recorded into, which the caller submits; null: submitted here.
    GeometryBuffers(wgpu::Device device,
                    const scene::SceneData& scene,
                    std::uint64_t maxSharedBufferBytes = 0,
                    StagedGeometry* staged = nullptr,
                    gpu::ResourcePool* pool = nullptr,
                    wgpu::CommandEncoder uploads = nullptr);
    // Hands the shared buffers to `pool` (the scene is being released: nothing binds them again).
    void giveBackTo(gpu::ResourcePool& pool);

    // Bindings of `primitive` for the attributes with these semantics (those the shader
    // variant consumes; absent ones are skipped).
    Result<PrimitiveBindings> bind(const scene::Primitive& primitive,
                                   std::span<const scene::Semantic> semantics) const;

    // GPU buffers created: the shared ones (one unless the geometry passes maxBufferSize) and
    // the private padded copies.
    std::size_t bufferCount() const { return mSharedBuffers.size() + mPrivateBuffers.size(); }
    // The shared buffers (Vertex, Index and Storage usage: vertex pulling reads them too).
    std::span<const wgpu::Buffer> sharedBuffers() const { return mSharedBuffers; }
    // Where an accessor's data lies in the shared buffers, for shaders that pull vertices and
    // indices themselves: the buffer's index in sharedBuffers() and the byte offset of its first
    // element. nullopt when its bufferView was not uploaded in place (only a padded copy).
    struct SharedPlacement {
        std::size_t buffer = 0;
        std::uint64_t byteOffset = 0;
    };
    std::optional<SharedPlacement> sharedPlacement(scene::AccessorId accessor) const;

    // Bytes written to the GPU: shared buffers (gaps included) and padded copies.
    std::uint64_t uploadedBytes() const { return mUploadedBytes; }

  private:
    struct ViewPlacement {
        wgpu::Buffer buffer;
        std::uint64_t offset = 0;  // Of the view's first byte in `buffer`.
        std::uint64_t length = 0;
    };
    const ViewPlacement& viewPlacement(scene::BufferViewId view) const;
    void uploadViews(std::uint64_t maxSharedBufferBytes,
                     StagedGeometry* staged,
                     gpu::ResourcePool* pool,
                     wgpu::CommandEncoder uploads);
    void uploadRepackedAccessors();

    wgpu::Device mDevice;
    const scene::SceneData* mScene;
    std::vector<wgpu::Buffer> mSharedBuffers;
    std::map<scene::BufferViewId, ViewPlacement> mViews;
    std::map<scene::AccessorId, std::pair<wgpu::Buffer, std::uint32_t>> mPrivateBuffers;
    std::uint64_t mUploadedBytes = 0;
};

// The accessor's elements copied with a stride rounded up to a multiple of 4 (WebGPU requires
// it); `stride` receives that stride.
std::vector<std::uint8_t> paddedVertexElements(const scene::SceneData& scene,
                                               scene::AccessorId accessor,
                                               std::uint32_t& stride);

}  // namespace encore::render

namespace encore::render {

class RenderEncoder;
struct RenderSetup;

// The pipeline key for drawing `bindings` with a shader variant into the setup's target:
// the bindings' vertex layouts plus topology, strip index format and attachment formats.
PipelineKey meshPipelineKey(const RenderSetup& setup,
                            const PrimitiveBindings& bindings,
                            const shaders::ShaderVariantKey& shader);

// Sets the primitive's vertex buffers (with their offsets) and index buffer.
void bindGeometry(RenderEncoder& encoder, const PrimitiveBindings& bindings);

// Draws the bound primitive: drawIndexed or draw, for `instanceCount` instances.
void drawGeometry(RenderEncoder& encoder,
                  const PrimitiveBindings& bindings,
                  std::uint32_t instanceCount,
                  std::uint32_t firstInstance);

}  // namespace encore::render
