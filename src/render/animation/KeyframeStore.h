#pragma once

// The float storage of GPU-evaluated animation (GpuAnimation's keyframe buffer): each distinct
// run of key times or key values is stored once, however many samplers use it, so that many
// copies of one animated model (a crowd's characters, each with its own animation over the same
// accessors) cost the GPU one set of keyframes.

#include <cstddef>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <utility>
#include <vector>

namespace encore::render {

class KeyframeStore {
  public:
    // Where `floats` starts in the store, appending it unless an equal run (bit for bit) is
    // stored already.
    std::uint32_t add(std::span<const float> floats);
    // Appended as they are, never shared: data the GPU indexes per node (rest weights).
    std::uint32_t append(std::span<const float> floats);

    std::size_t size() const { return mFloats.size(); }
    const std::vector<float>& floats() const { return mFloats; }
    std::vector<float> take() { return std::move(mFloats); }

  private:
    std::vector<float> mFloats;
    // Hash of a run's bytes -> (offset, count) of the shared runs with that hash.
    std::unordered_multimap<std::size_t, std::pair<std::uint32_t, std::size_t>> mRuns;
};

}  // namespace encore::render
