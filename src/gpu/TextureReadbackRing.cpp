#include "gpu/TextureReadbackRing.h"

#include <algorithm>
#include <chrono>
#include <string>

#include "core/Elapsed.h"
#include "gpu/Readback.h"

namespace encore::gpu {

struct TextureReadbackRing::Slot {
    wgpu::Buffer buffer;
    wgpu::Future future;
    std::uint64_t ticket = 0;
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::uint32_t paddedRowBytes = 0;
    std::uint32_t bytesPerTexel = 4;
    std::uint64_t size = 0;  // Mapped.
    // Set by the map callback, which runs inside Context::wait (WaitAnyOnly).
    bool mapped = false;
    std::string mapMessage;
    // Taken with takeOldestMapped and still mapped: `held` until the ring unmaps it, `released`
    // (guarded by Releases::mutex) once the last holder let go.
    bool held = false;
    bool released = false;
};

TextureReadbackRing::TextureReadbackRing(Context& context, std::size_t slots) : mContext(&context) {
    for (std::size_t i = 0; i < std::max<std::size_t>(slots, 1); ++i) {
        mSlots.push_back(std::make_shared<Slot>());
    }
}

TextureReadbackRing::~TextureReadbackRing() {
    for (Slot* slot : mInFlight) {
        mContext->wait(slot->future);
    }
    // Holders read the mapped rows: the buffers must outlive them.
    std::unique_lock lock(mReleases->mutex);
    for (const auto& slot : mSlots) {
        mReleases->released.wait(lock, [&] { return !slot->held || slot->released; });
    }
}

bool TextureReadbackRing::oldestReady() const {
    return !mInFlight.empty() && mContext->wait(mInFlight.front()->future, 0);
}

TextureReadbackRing::Slot* TextureReadbackRing::freeSlot() {
    const auto inFlight = [&](const Slot* slot) {
        return std::find(mInFlight.begin(), mInFlight.end(), slot) != mInFlight.end();
    };
    std::unique_lock lock(mReleases->mutex);
    while (true) {
        bool anyHeld = false;
        for (const auto& slot : mSlots) {
            if (inFlight(slot.get())) {
                continue;
            }
            if (!slot->held) {
                return slot.get();
            }
            anyHeld = true;
            if (slot->released) {
                slot->buffer.Unmap();
                slot->held = false;
                slot->released = false;
                return slot.get();
            }
        }
        if (!anyHeld) {
            return nullptr;
        }
        mReleases->released.wait(lock);
    }
}

namespace {

// Replaces a slot's buffer by one of `bytes` when it has none that large.
void growSlotBuffer(wgpu::Buffer& buffer, const wgpu::Device& device, std::uint64_t bytes) {
    if (buffer && buffer.GetSize() >= bytes) {
        return;
    }
    wgpu::BufferDescriptor descriptor{};
    descriptor.label = "read-back ring slot";
    descriptor.size = bytes;
    descriptor.usage = wgpu::BufferUsage::CopyDst | wgpu::BufferUsage::MapRead;
    buffer = device.CreateBuffer(&descriptor);
}

}  // namespace

void TextureReadbackRing::reserve(std::uint64_t bytes) {
    bytes =
        std::min<std::uint64_t>((bytes + 3) & ~std::uint64_t{3}, mContext->limits().maxBufferSize);
    for (const auto& slot : mSlots) {
        growSlotBuffer(slot->buffer, mContext->device(), bytes);
    }
}

Result<TextureReadbackRing::Slot*> TextureReadbackRing::slotFor(std::uint64_t size,
                                                                const std::string& what) {
    Slot* slot = full() ? nullptr : freeSlot();
    if (!slot) {
        return makeError(ErrorCode::InvalidArgument, "Every read-back slot is in use (" +
                                                         std::to_string(mSlots.size()) +
                                                         "); take a finished read first.");
    }
    if (size > mContext->limits().maxBufferSize) {
        return makeError(ErrorCode::LimitExceeded,
                         what + " needs a buffer of " + std::to_string(size) +
                             " bytes, more than the device's maxBufferSize (" +
                             std::to_string(mContext->limits().maxBufferSize) + " bytes).");
    }
    growSlotBuffer(slot->buffer, mContext->device(), size);
    return slot;
}

std::uint64_t TextureReadbackRing::submitAndMap(Slot& slot,
                                                const wgpu::CommandEncoder& encoder,
                                                std::uint64_t size) {
    wgpu::CommandBuffer commands = encoder.Finish();
    mContext->queue().Submit(1, &commands);
    slot.size = size;
    slot.mapped = false;
    slot.mapMessage.clear();
    slot.ticket = mNextTicket++;
    Slot* mapping = &slot;
    slot.future =
        slot.buffer.MapAsync(wgpu::MapMode::Read, 0, size, wgpu::CallbackMode::WaitAnyOnly,
                             [mapping](wgpu::MapAsyncStatus status, wgpu::StringView message) {
                                 mapping->mapped = status == wgpu::MapAsyncStatus::Success;
                                 mapping->mapMessage = std::string(std::string_view(message));
                             });
    mInFlight.push_back(&slot);
    return slot.ticket;
}

Result<std::uint64_t> TextureReadbackRing::enqueue(const wgpu::Texture& texture,
                                                   StageTimestamps* timestamps,
                                                   std::uint32_t stage) {
    const wgpu::TextureFormat format = texture.GetFormat();
    const bool halves = format == wgpu::TextureFormat::RGBA16Float;
    if (format != wgpu::TextureFormat::RGBA8Unorm &&
        format != wgpu::TextureFormat::RGBA8UnormSrgb && !halves) {
        return makeError(ErrorCode::InvalidArgument,
                         "TextureReadbackRing reads RGBA8 and RGBA16Float textures only.");
    }
    const std::uint32_t width = texture.GetWidth();
    const std::uint32_t height = texture.GetHeight();
    const std::uint32_t bytesPerTexel = halves ? 8 : 4;
    const std::uint32_t rowBytes = paddedRowBytes(width * bytesPerTexel);
    const std::uint64_t size = std::uint64_t(rowBytes) * height;
    ENCORE_TRY_ASSIGN(Slot * slot, slotFor(size, "Reading back a " + std::to_string(width) + "x" +
                                                     std::to_string(height) + " texture"));
    slot->width = width;
    slot->height = height;
    slot->bytesPerTexel = bytesPerTexel;
    slot->paddedRowBytes = rowBytes;
    wgpu::TexelCopyTextureInfo source{};
    source.texture = texture;
    wgpu::TexelCopyBufferInfo destination{};
    destination.buffer = slot->buffer;
    destination.layout.bytesPerRow = slot->paddedRowBytes;
    destination.layout.rowsPerImage = slot->height;
    wgpu::Extent3D extent{slot->width, slot->height, 1};
    wgpu::CommandEncoder encoder = mContext->device().CreateCommandEncoder();
    if (timestamps) {
        timestamps->timeCommands(
            encoder, stage, [&] { encoder.CopyTextureToBuffer(&source, &destination, &extent); });
    } else {
        encoder.CopyTextureToBuffer(&source, &destination, &extent);
    }
    return submitAndMap(*slot, encoder, size);
}

Result<std::uint64_t> TextureReadbackRing::enqueueCommands(
    std::uint64_t size,
    const std::function<void(const wgpu::CommandEncoder&, const wgpu::Buffer&)>& record,
    StageTimestamps* timestamps,
    std::uint32_t stage) {
    ENCORE_TRY_ASSIGN(Slot * slot, slotFor(size, "A read-back of GPU-written bytes"));
    slot->width = 0;
    slot->height = 0;
    slot->bytesPerTexel = 0;
    slot->paddedRowBytes = 0;
    wgpu::CommandEncoder encoder = mContext->device().CreateCommandEncoder();
    if (timestamps) {
        timestamps->timeCommands(encoder, stage, [&] { record(encoder, slot->buffer); });
    } else {
        record(encoder, slot->buffer);
    }
    return submitAndMap(*slot, encoder, size);
}

Result<MappedReadback> TextureReadbackRing::takeOldestMapped() {
    if (mInFlight.empty()) {
        return makeError(ErrorCode::InvalidArgument, "No read-back is in flight.");
    }
    Slot* slot = mInFlight.front();
    mInFlight.pop_front();
    MappedReadback finished;
    finished.ticket = slot->ticket;
    const auto waitStart = std::chrono::steady_clock::now();
    mContext->wait(slot->future);
    finished.waitMilliseconds = millisecondsSince(waitStart);
    if (!slot->mapped) {
        return makeError(ErrorCode::DeviceError,
                         "Mapping a read-back buffer failed (" + slot->mapMessage + ").");
    }
    const std::uint64_t size = slot->size;
    finished.size = size;
    finished.width = slot->width;
    finished.height = slot->height;
    finished.bytesPerRow = slot->paddedRowBytes;
    finished.bytesPerTexel = slot->bytesPerTexel;
    finished.rows = static_cast<const std::uint8_t*>(slot->buffer.GetConstMappedRange(0, size));
    slot->held = true;
    slot->released = false;
    // The last holder marks the slot released; this ring unmaps it on its own thread.
    const auto owner = std::find_if(mSlots.begin(), mSlots.end(),
                                    [&](const auto& candidate) { return candidate.get() == slot; });
    finished.hold =
        std::shared_ptr<const void>(slot, [keep = *owner, releases = mReleases](const void*) {
            {
                std::lock_guard lock(releases->mutex);
                keep->released = true;
            }
            releases->released.notify_all();
        });
    return finished;
}

Result<FinishedReadback> TextureReadbackRing::takeOldest() {
    ENCORE_TRY_ASSIGN(auto mapped, takeOldestMapped());
    if (mapped.bytesPerTexel != 4) {
        return makeError(
            ErrorCode::InvalidArgument,
            "takeOldest returns RGBA8 images: take a float read with takeOldestMapped.");
    }
    FinishedReadback finished;
    finished.ticket = mapped.ticket;
    finished.waitMilliseconds = mapped.waitMilliseconds;
    const auto copyStart = std::chrono::steady_clock::now();
    const std::uint32_t rowBytes = mapped.width * 4;
    finished.image.width = mapped.width;
    finished.image.height = mapped.height;
    finished.image.pixels.resize(std::size_t(rowBytes) * mapped.height);
    unpadRows(mapped.rows, rowBytes, mapped.height, finished.image.pixels.data());
    finished.copyMilliseconds = millisecondsSince(copyStart);
    return finished;  // `mapped` lets go of the slot: the next enqueue unmaps it.
}

}  // namespace encore::gpu
