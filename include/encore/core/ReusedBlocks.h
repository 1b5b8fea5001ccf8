#pragma once

// Large byte buffers that the process reuses instead of asking the allocator and the kernel for
// fresh memory each time: decoded images, whose sizes repeat from model to model.
//
// A freed block of a few megabytes goes back to the kernel or to the end of an arena that glibc
// may unmap (a thread arena's heap is deleted when it empties); the next image of that size then
// faults in zeroed pages again, and the decoder (through std::vector's resize) zeroes them once
// more before writing every byte itself. In a batch of the ten shared models that was half of
// the loaders' CPU (issue 48). Blocks of at least kReusedBlockBytes are kept here when freed and
// handed out again for the same size class; the allocator below also leaves new elements
// default-initialised (no zeroing) when a vector grows.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <new>
#include <utility>
#include <vector>

namespace encore {

// Smaller blocks go to operator new: glibc's bins and thread caches serve them without the
// kernel.
inline constexpr std::size_t kReusedBlockBytes = std::size_t(256) << 10;

// A block of at least `bytes` (>= kReusedBlockBytes) for the caller alone: a kept one of its
// size class when there is one, else a new one. Throws std::bad_alloc when memory is exhausted.
void* takeReusedBlock(std::size_t bytes);
// Gives back a block that takeReusedBlock(bytes) returned, with the same `bytes`: kept for the
// next take of its class while the kept blocks stay within reusedBlockLimit(), else freed.
void giveReusedBlock(void* block, std::size_t bytes) noexcept;

struct ReusedBlockCounts {
    std::uint64_t taken = 0;         // takeReusedBlock calls.
    std::uint64_t created = 0;       // Of those, the ones no kept block served.
    std::uint64_t createdBytes = 0;  // Their bytes (rounded to the size class).
    std::uint64_t keptBytes = 0;     // Held now for later takes.
};
ReusedBlockCounts reusedBlockCounts();

// The most bytes kept for reuse (default 512 MiB; 0 keeps none). Lowering it frees what is over.
void setReusedBlockLimit(std::uint64_t bytes);
std::uint64_t reusedBlockLimit();

// An allocator for vectors of trivial elements that takes large blocks through takeReusedBlock
// and default-initialises new elements: resize() leaves them unset, for writers that set every
// one (decoders). Stateless: every instance equals every other.
template <class T>
struct ReusedAllocator {
    using value_type = T;

    ReusedAllocator() noexcept = default;
    template <class U>
    ReusedAllocator(const ReusedAllocator<U>&) noexcept {}

    T* allocate(std::size_t count) {
        const std::size_t bytes = count * sizeof(T);
        if (count > SIZE_MAX / sizeof(T)) {
            throw std::bad_alloc();
        }
        if (bytes >= kReusedBlockBytes) {
            return static_cast<T*>(takeReusedBlock(bytes));
        }
        return static_cast<T*>(::operator new(bytes));
    }
    void deallocate(T* pointer, std::size_t count) noexcept {
        const std::size_t bytes = count * sizeof(T);
        if (bytes >= kReusedBlockBytes) {
            giveReusedBlock(pointer, bytes);
        } else {
            ::operator delete(pointer);
        }
    }

    template <class U>
    void construct(U* pointer) noexcept(noexcept(::new(static_cast<void*>(pointer)) U)) {
        ::new (static_cast<void*>(pointer)) U;
    }
    template <class U, class... Args>
    void construct(U* pointer, Args&&... args) {
        ::new (static_cast<void*>(pointer)) U(std::forward<Args>(args)...);
    }

    template <class U>
    bool operator==(const ReusedAllocator<U>&) const noexcept {
        return true;
    }
};

// Bytes in reused blocks; resize() does not zero what it adds.
using ReusedBytes = std::vector<std::uint8_t, ReusedAllocator<std::uint8_t>>;

// The same bytes as a plain vector's (found by argument-dependent lookup, either order).
inline bool operator==(const ReusedBytes& bytes, const std::vector<std::uint8_t>& other) {
    return std::equal(bytes.begin(), bytes.end(), other.begin(), other.end());
}

}  // namespace encore
