#pragma once

// Where the glTF bufferViews that a scene's primitives read in place lie in the GPU scene's
// shared geometry buffers (VertexBindings.h): each view at a 4-byte-aligned offset, a new buffer
// begun only where the next view would pass `maxBufferBytes`. GeometryBuffers creates its buffers
// by it, and StagedGeometry stages their bytes by it ahead of the upload, so both must agree.

#include <cstdint>
#include <vector>

#include "encore/scene/SceneData.h"

namespace encore::render {

// Whether a vertex attribute can be bound where it lies in its bufferView (its offset and stride
// multiples of 4, the stride within WebGPU's limit); others are copied into padded buffers.
bool readsInPlace(const scene::Accessor& accessor);

struct SharedGeometryLayout {
    struct View {
        scene::BufferViewId id;
        std::uint64_t offset = 0;  // Of the view's first byte in its buffer.
        std::uint64_t length = 0;
        friend bool operator==(const View&, const View&) = default;
    };
    struct Buffer {
        std::uint64_t size = 0;  // Up to the last view's end (the GPU buffer rounds it up to 4).
        std::vector<View> views;
        friend bool operator==(const Buffer&, const Buffer&) = default;
    };
    std::vector<Buffer> buffers;
    friend bool operator==(const SharedGeometryLayout&, const SharedGeometryLayout&) = default;
};

// Every view read in place (those of in-place attributes and of indices), in view order.
SharedGeometryLayout sharedGeometryLayout(const scene::SceneData& scene,
                                          std::uint64_t maxBufferBytes);

}  // namespace encore::render
