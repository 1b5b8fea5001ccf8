#pragma once

// A byte buffer that a thread keeps from one image to the next (as a thread_local): the PNG
// encoder and decoder work on thousands of same-sized images on the same few threads, and fresh
// megabytes cost as much in allocation and page faults as the work done in them. A buffer that
// grew past its owner's limit for a one-off large image is freed after use instead of kept.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>

namespace encore::image {

class ScratchBuffer {
  public:
    // Buffers up to `keptBytes` are kept between uses.
    explicit ScratchBuffer(std::size_t keptBytes) : mKeptBytes(keptBytes) {}

    // At least `bytes` bytes, not zeroed; null when they cannot be allocated.
    std::uint8_t* reserve(std::size_t bytes) {
        if (mCapacity < bytes) {
            mBytes.reset(new (std::nothrow) std::uint8_t[bytes]);
            mCapacity = mBytes ? bytes : 0;
        }
        return mBytes.get();
    }

    // Frees the buffer if it is larger than a buffer worth keeping.
    void releaseIfLarge() {
        if (mCapacity > mKeptBytes) {
            mBytes.reset();
            mCapacity = 0;
        }
    }

    // Calls releaseIfLarge when the scope that used the buffer ends, however it ends.
    class Use {
      public:
        explicit Use(ScratchBuffer& buffer) : mBuffer(buffer) {}
        ~Use() { mBuffer.releaseIfLarge(); }
        Use(const Use&) = delete;
        Use& operator=(const Use&) = delete;

      private:
        ScratchBuffer& mBuffer;
    };

  private:
    std::size_t mKeptBytes;
    std::unique_ptr<std::uint8_t[]> mBytes;
    std::size_t mCapacity = 0;
};

}  // namespace encore::image
