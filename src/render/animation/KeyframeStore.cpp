#include "render/animation/KeyframeStore.h"

#include <cstring>
#include <functional>
#include <string_view>

namespace encore::render {

std::uint32_t KeyframeStore::add(std::span<const float> floats) {
    const std::string_view bytes(reinterpret_cast<const char*>(floats.data()), floats.size_bytes());
    const std::size_t hash = std::hash<std::string_view>{}(bytes);
    auto [first, last] = mRuns.equal_range(hash);
    for (auto it = first; it != last; ++it) {
        const auto [offset, count] = it->second;
        if (count == floats.size() &&
            std::memcmp(mFloats.data() + offset, floats.data(), floats.size_bytes()) == 0) {
            return offset;
        }
    }
    const std::uint32_t offset = append(floats);
    mRuns.emplace(hash, std::pair(offset, floats.size()));
    return offset;
}

std::uint32_t KeyframeStore::append(std::span<const float> floats) {
    const auto offset = static_cast<std::uint32_t>(mFloats.size());
    mFloats.insert(mFloats.end(), floats.begin(), floats.end());
    return offset;
}

}  // namespace encore::render
