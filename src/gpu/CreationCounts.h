#pragma once

// What the calling thread has asked WebGPU to create: the objects that take memory from the
// driver (buffers, textures, query sets) and the bytes of buffers created mappable. Counted for
// every call into Dawn's CreateBuffer/CreateTexture/CreateQuerySet made by Encore's code: the
// build wraps those three entry points (the linker's --wrap, src/gpu/CMakeLists.txt), so no call
// site can be missed. A batch's device thread reads the difference around each model
// (metadata.json's `gpu`): in steady state a model should create nothing, since every creation
// is a round trip into the driver's allocator (issue 48: about 50 ioctls per model on the H200).
//
// ENCORE_TRACE_GPU_CREATION=1 prints each creation (kind, label, bytes) to stderr: where the
// objects a model still creates come from.

#include <cstdint>

namespace encore::gpu {

struct CreationCounts {
    std::uint64_t buffers = 0;
    std::uint64_t textures = 0;
    std::uint64_t querySets = 0;
    // Bytes of buffers created with MapRead or MapWrite usage or mapped at creation: memory the
    // driver maps into the process afresh.
    std::uint64_t bytesMapped = 0;

    std::uint64_t objects() const { return buffers + textures + querySets; }

    CreationCounts operator-(const CreationCounts& earlier) const {
        return {buffers - earlier.buffers, textures - earlier.textures,
                querySets - earlier.querySets, bytesMapped - earlier.bytesMapped};
    }
};

// Everything the calling thread has created so far.
CreationCounts threadCreationCounts();

}  // namespace encore::gpu
