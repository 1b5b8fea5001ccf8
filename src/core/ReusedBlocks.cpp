#include "encore/core/ReusedBlocks.h"

#include <algorithm>
#include <bit>
#include <cstdlib>
#include <mutex>
#include <unordered_map>

namespace encore {
namespace {

// Sizes round up to an eighth of their power of two (at most 12.5% more), so that images of
// nearly the same size share blocks.
std::size_t sizeClass(std::size_t bytes) {
    const std::size_t step = std::max<std::size_t>(std::bit_floor(bytes) / 8, 64 << 10);
    return (bytes + step - 1) / step * step;
}

class BlockShelf {
  public:
    void* take(std::size_t bytes) {
        const std::size_t size = sizeClass(bytes);
        {
            const std::lock_guard lock(mMutex);
            ++mCounts.taken;
            if (auto found = mKept.find(size); found != mKept.end() && !found->second.empty()) {
                void* block = found->second.back();
                found->second.pop_back();
                mCounts.keptBytes -= size;
                return block;
            }
            ++mCounts.created;
            mCounts.createdBytes += size;
        }
        void* block = std::malloc(size);
        if (!block) {
            throw std::bad_alloc();
        }
        return block;
    }

    void give(void* block, std::size_t bytes) noexcept {
        const std::size_t size = sizeClass(bytes);
        {
            const std::lock_guard lock(mMutex);
            if (mCounts.keptBytes + size <= mLimit) {
                try {
                    mKept[size].push_back(block);
                    mCounts.keptBytes += size;
                    return;
                } catch (const std::bad_alloc&) {
                    // No room to list it: free it instead.
                }
            }
        }
        std::free(block);
    }

    void setLimit(std::uint64_t bytes) {
        std::vector<void*> freed;
        {
            const std::lock_guard lock(mMutex);
            mLimit = bytes;
            for (auto& [size, blocks] : mKept) {
                while (mCounts.keptBytes > mLimit && !blocks.empty()) {
                    freed.push_back(blocks.back());
                    blocks.pop_back();
                    mCounts.keptBytes -= size;
                }
            }
        }
        for (void* block : freed) {
            std::free(block);
        }
    }

    std::uint64_t limit() {
        const std::lock_guard lock(mMutex);
        return mLimit;
    }

    ReusedBlockCounts counts() {
        const std::lock_guard lock(mMutex);
        return mCounts;
    }

  private:
    std::mutex mMutex;
    std::unordered_map<std::size_t, std::vector<void*>> mKept;  // By size class.
    std::uint64_t mLimit = std::uint64_t{512} << 20;
    ReusedBlockCounts mCounts;
};

// Never destroyed: vectors of static objects may give blocks back during exit.
BlockShelf& shelf() {
    static BlockShelf* const instance = new BlockShelf;
    return *instance;
}

}  // namespace

void* takeReusedBlock(std::size_t bytes) {
    return shelf().take(bytes);
}

void giveReusedBlock(void* block, std::size_t bytes) noexcept {
    shelf().give(block, bytes);
}

ReusedBlockCounts reusedBlockCounts() {
    return shelf().counts();
}

void setReusedBlockLimit(std::uint64_t bytes) {
    shelf().setLimit(bytes);
}

std::uint64_t reusedBlockLimit() {
    return shelf().limit();
}

}  // namespace encore
