#pragma once

// GPU buffers and textures kept from one scene to the next, so that a batch's steady state
// creates none (issue 48). On the H200 every creation of a texture or large buffer is a round
// trip through the driver's allocator (vidmem allocation, GPU and CPU mappings: about 50 ioctls
// per model of 200 us each, serialised with every other thread's memory-map changes in the
// process); a texture or buffer taken from here is one the driver already holds.
//
// A scene takes what it uploads into from the pool (texture(), buffer()) and gives it back when
// it is released (giveBack()). What is given back is handed out again only for a request of the
// same description: textures by format, size, mip count, sample count and usage; buffers by
// usage and size, exactly, since shaders and bindings read a buffer's size (arrayLength, whole
// bindings). Reuse needs no wait for the GPU: the next scene's writes are queued after every
// command that read the old contents. Only resources that can be written again (CopyDst usage)
// are kept, at most `keptBytes` of them, the longest unused given up first.
//
// Only the thread that owns the device calls this object.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <list>
#include <span>
#include <string>

namespace encore::gpu {

class ResourcePool {
  public:
    explicit ResourcePool(wgpu::Device device, std::uint64_t keptBytes = std::uint64_t{1} << 30);

    // A texture as `descriptor` describes (its label names a new one): a kept one when one
    // matches, else created. Its contents are undefined: the caller writes every level it reads.
    wgpu::Texture texture(const wgpu::TextureDescriptor& descriptor);
    // A buffer of `size` bytes (rounded up to 4) with `usage`: a kept one of that size and usage,
    // else created (zeroed). Its contents are undefined: the caller writes what it reads.
    wgpu::Buffer buffer(wgpu::BufferUsage usage, std::uint64_t size, const std::string& label);
    // A buffer as buffer() gives (`usage` must include CopyDst) holding `bytes`, zero-padded to
    // its size, written through `queue`: createBufferWithData's counterpart for kept buffers.
    wgpu::Buffer bufferWithData(const wgpu::Queue& queue,
                                wgpu::BufferUsage usage,
                                std::span<const std::uint8_t> bytes,
                                const std::string& label);

    // Takes back a texture or buffer no command recorded later will use; kept when it can be
    // written again and fits within keptBytes, otherwise released.
    void giveBack(wgpu::Texture texture);
    void giveBack(wgpu::Buffer buffer);

    // Requests served from kept resources, and by creating new ones.
    std::uint64_t reused() const { return mReused; }
    std::uint64_t created() const { return mCreated; }
    std::uint64_t keptBytes() const { return mBytes; }

  private:
    struct Kept {
        wgpu::Texture texture;
        wgpu::Buffer buffer;
        std::uint64_t bytes = 0;
    };
    void keep(Kept kept);
    // Removes the most recently given back resource that `matches` accepts and returns it; an
    // empty Kept when there is none (counted as reuse or creation for the caller).
    template <typename Matches>
    Kept take(Matches&& matches);

    wgpu::Device mDevice;
    std::uint64_t mKeptBytesLimit;
    std::uint64_t mBytes = 0;
    std::list<Kept> mKept;  // Most recently given back first.
    std::uint64_t mReused = 0;
    std::uint64_t mCreated = 0;
};

// A buffer holding `bytes` (zero-padded to a multiple of 4): from `pool` and written through
// `queue` when there is a pool, else created mapped (createBufferWithData). `usage` must include
// CopyDst when a pool is given.
wgpu::Buffer bufferWithData(ResourcePool* pool,
                            const wgpu::Device& device,
                            const wgpu::Queue& queue,
                            wgpu::BufferUsage usage,
                            std::span<const std::uint8_t> bytes,
                            const std::string& label);

}  // namespace encore::gpu
