#include "encore/gpu/TextureReadbackRing.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <string>

#include "encore/core/Elapsed.h"

namespace encore::gpu {

struct TextureReadbackRing::Slot {
    wgpu::Buffer buffer;
    wgpu::Future future;
    std::uint64_t ticket = 0;
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::uint32_t paddedRowBytes = 0;
    // Set by the map callback, which runs inside Context::wait (WaitAnyOnly).
    bool mapped = false;
    std::string mapMessage;
};

TextureReadbackRing::TextureReadbackRing(Context& context, std::size_t slots) : mContext(&context) {
    for (std::size_t i = 0; i < std::max<std::size_t>(slots, 1); ++i) {
        mSlots.push_back(std::make_unique<Slot>());
    }
}

TextureReadbackRing::~TextureReadbackRing() {
    for (Slot* slot : mInFlight) {
        mContext->wait(slot->future);
    }
}

bool TextureReadbackRing::oldestReady() const {
    return !mInFlight.empty() && mContext->wait(mInFlight.front()->future, 0);
}

Result<std::uint64_t> TextureReadbackRing::enqueue(const wgpu::Texture& texture) {
    if (full()) {
        return makeError(ErrorCode::InvalidArgument, "Every read-back slot is in use (" +
                                                         std::to_string(mSlots.size()) +
                                                         "); take a finished read first.");
    }
    const wgpu::TextureFormat format = texture.GetFormat();
    if (format != wgpu::TextureFormat::RGBA8Unorm &&
        format != wgpu::TextureFormat::RGBA8UnormSrgb) {
        return makeError(ErrorCode::InvalidArgument,
                         "TextureReadbackRing reads RGBA8 textures only.");
    }
    Slot* slot = nullptr;
    for (const auto& candidate : mSlots) {
        if (std::find(mInFlight.begin(), mInFlight.end(), candidate.get()) == mInFlight.end()) {
            slot = candidate.get();
            break;
        }
    }
    slot->width = texture.GetWidth();
    slot->height = texture.GetHeight();
    // Buffer copies need rows aligned to 256 bytes.
    slot->paddedRowBytes = (slot->width * 4 + 255) / 256 * 256;
    const std::uint64_t size = std::uint64_t(slot->paddedRowBytes) * slot->height;
    if (size > mContext->limits().maxBufferSize) {
        return makeError(ErrorCode::LimitExceeded,
                         "Reading back a " + std::to_string(slot->width) + "x" +
                             std::to_string(slot->height) + " texture needs a buffer of " +
                             std::to_string(size) +
                             " bytes, more than the device's maxBufferSize (" +
                             std::to_string(mContext->limits().maxBufferSize) + " bytes).");
    }
    if (!slot->buffer || slot->buffer.GetSize() < size) {
        wgpu::BufferDescriptor descriptor{};
        descriptor.label = "read-back ring slot";
        descriptor.size = size;
        descriptor.usage = wgpu::BufferUsage::CopyDst | wgpu::BufferUsage::MapRead;
        slot->buffer = mContext->device().CreateBuffer(&descriptor);
    }
    wgpu::TexelCopyTextureInfo source{};
    source.texture = texture;
    wgpu::TexelCopyBufferInfo destination{};
    destination.buffer = slot->buffer;
    destination.layout.bytesPerRow = slot->paddedRowBytes;
    destination.layout.rowsPerImage = slot->height;
    wgpu::Extent3D extent{slot->width, slot->height, 1};
    wgpu::CommandEncoder encoder = mContext->device().CreateCommandEncoder();
    encoder.CopyTextureToBuffer(&source, &destination, &extent);
    wgpu::CommandBuffer commands = encoder.Finish();
    mContext->queue().Submit(1, &commands);

    slot->mapped = false;
    slot->mapMessage.clear();
    slot->ticket = mNextTicket++;
    slot->future =
        slot->buffer.MapAsync(wgpu::MapMode::Read, 0, size, wgpu::CallbackMode::WaitAnyOnly,
                              [slot](wgpu::MapAsyncStatus status, wgpu::StringView message) {
                                  slot->mapped = status == wgpu::MapAsyncStatus::Success;
                                  slot->mapMessage = std::string(std::string_view(message));
                              });
    mInFlight.push_back(slot);
    return slot->ticket;
}

Result<FinishedReadback> TextureReadbackRing::takeOldest() {
    if (mInFlight.empty()) {
        return makeError(ErrorCode::InvalidArgument, "No read-back is in flight.");
    }
    Slot* slot = mInFlight.front();
    mInFlight.pop_front();
    FinishedReadback finished;
    finished.ticket = slot->ticket;
    const auto waitStart = std::chrono::steady_clock::now();
    mContext->wait(slot->future);
    finished.waitMilliseconds = millisecondsSince(waitStart);
    if (!slot->mapped) {
        return makeError(ErrorCode::DeviceError,
                         "Mapping a read-back buffer failed (" + slot->mapMessage + ").");
    }
    const auto copyStart = std::chrono::steady_clock::now();
    const std::uint64_t size = std::uint64_t(slot->paddedRowBytes) * slot->height;
    const auto* mapped =
        static_cast<const std::uint8_t*>(slot->buffer.GetConstMappedRange(0, size));
    finished.image.width = slot->width;
    finished.image.height = slot->height;
    const std::size_t rowBytes = std::size_t(slot->width) * 4;
    finished.image.pixels.resize(rowBytes * slot->height);
    for (std::uint32_t y = 0; y < slot->height; ++y) {
        std::memcpy(&finished.image.pixels[y * rowBytes],
                    mapped + std::size_t(y) * slot->paddedRowBytes, rowBytes);
    }
    slot->buffer.Unmap();
    finished.copyMilliseconds = millisecondsSince(copyStart);
    return finished;
}

}  // namespace encore::gpu
