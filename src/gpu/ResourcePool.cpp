#include "gpu/ResourcePool.h"

#include <algorithm>
#include <utility>

#include "gpu/Upload.h"

namespace encore::gpu {
namespace {

bool sameTexture(const wgpu::Texture& texture, const wgpu::TextureDescriptor& descriptor) {
    // An undefined dimension is 2D.
    const wgpu::TextureDimension dimension =
        descriptor.dimension == wgpu::TextureDimension::Undefined ? wgpu::TextureDimension::e2D
                                                                  : descriptor.dimension;
    return texture.GetFormat() == descriptor.format && texture.GetDimension() == dimension &&
           texture.GetWidth() == descriptor.size.width &&
           texture.GetHeight() == descriptor.size.height &&
           texture.GetDepthOrArrayLayers() == descriptor.size.depthOrArrayLayers &&
           texture.GetMipLevelCount() == descriptor.mipLevelCount &&
           texture.GetSampleCount() == descriptor.sampleCount &&
           texture.GetUsage() == descriptor.usage && descriptor.viewFormatCount == 0;
}

// What a texture holds, mip chain included (the chain adds at most a third).
std::uint64_t textureBytes(const wgpu::Texture& texture) {
    const std::uint64_t level0 = std::uint64_t(texture.GetWidth()) * texture.GetHeight() *
                                 texture.GetDepthOrArrayLayers() * texture.GetSampleCount() * 4;
    return texture.GetMipLevelCount() > 1 ? level0 + level0 / 3 : level0;
}

}  // namespace

ResourcePool::ResourcePool(wgpu::Device device, std::uint64_t keptBytes)
    : mDevice(std::move(device)), mKeptBytesLimit(keptBytes) {}

template <typename Matches>
ResourcePool::Kept ResourcePool::take(Matches&& matches) {
    const auto found = std::find_if(mKept.begin(), mKept.end(), matches);
    if (found == mKept.end()) {
        ++mCreated;
        return {};
    }
    Kept kept = std::move(*found);
    mBytes -= kept.bytes;
    mKept.erase(found);
    ++mReused;
    return kept;
}

wgpu::Texture ResourcePool::texture(const wgpu::TextureDescriptor& descriptor) {
    Kept kept = take([&](const Kept& candidate) {
        return candidate.texture && sameTexture(candidate.texture, descriptor);
    });
    return kept.texture ? std::move(kept.texture) : mDevice.CreateTexture(&descriptor);
}

wgpu::Buffer ResourcePool::buffer(wgpu::BufferUsage usage,
                                  std::uint64_t size,
                                  const std::string& label) {
    const std::uint64_t bytes = bufferSizeFor(size);
    Kept kept = take([&](const Kept& candidate) {
        return candidate.buffer && candidate.buffer.GetUsage() == usage &&
               candidate.buffer.GetSize() == bytes;
    });
    return kept.buffer ? std::move(kept.buffer) : createBuffer(mDevice, usage, bytes, label);
}

wgpu::Buffer ResourcePool::bufferWithData(const wgpu::Queue& queue,
                                          wgpu::BufferUsage usage,
                                          std::span<const std::uint8_t> bytes,
                                          const std::string& label) {
    wgpu::Buffer buffer = this->buffer(usage, bytes.size(), label);
    const std::uint64_t whole = bytes.size() & ~std::uint64_t{3};
    if (whole > 0) {
        queue.WriteBuffer(buffer, 0, bytes.data(), whole);
    }
    // The last partial word and the padding: WriteBuffer writes whole words.
    std::uint8_t tail[4] = {};
    std::copy(bytes.begin() + std::ptrdiff_t(whole), bytes.end(), tail);
    if (whole < buffer.GetSize()) {
        queue.WriteBuffer(buffer, whole, tail, 4);
    }
    return buffer;
}

void ResourcePool::giveBack(wgpu::Texture texture) {
    if (texture && (texture.GetUsage() & wgpu::TextureUsage::CopyDst)) {
        const std::uint64_t bytes = textureBytes(texture);
        keep({std::move(texture), {}, bytes});
    }
}

void ResourcePool::giveBack(wgpu::Buffer buffer) {
    if (buffer && (buffer.GetUsage() & wgpu::BufferUsage::CopyDst) &&
        buffer.GetMapState() == wgpu::BufferMapState::Unmapped) {
        const std::uint64_t bytes = buffer.GetSize();
        keep({{}, std::move(buffer), bytes});
    }
}

void ResourcePool::keep(Kept kept) {
    if (kept.bytes > mKeptBytesLimit) {
        return;
    }
    mBytes += kept.bytes;
    mKept.push_front(std::move(kept));
    while (mBytes > mKeptBytesLimit) {
        mBytes -= mKept.back().bytes;
        mKept.pop_back();
    }
}

wgpu::Buffer bufferWithData(ResourcePool* pool,
                            const wgpu::Device& device,
                            const wgpu::Queue& queue,
                            wgpu::BufferUsage usage,
                            std::span<const std::uint8_t> bytes,
                            const std::string& label) {
    // A kept buffer is written through the queue: mapping at creation needs a new one.
    return pool ? pool->bufferWithData(queue, usage, bytes, label)
                : createBufferWithData(device, usage, bytes, label);
}

}  // namespace encore::gpu
