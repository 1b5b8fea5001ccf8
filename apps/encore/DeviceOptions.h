#pragma once

// The devices a command renders on: `--device N` (every command, or the ENCORE_DEVICE
// variable) and `encore batch --devices all|N,M,...`, as indices into gpu::listAdapters().

#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

#include "encore/core/Result.h"
#include "encore/gpu/Context.h"

namespace encore::app {

// "N": a device index, or an InvalidArgument error naming the text.
Result<std::size_t> parseDeviceIndex(std::string_view text);

// "all": every adapter like the first (gpu::adaptersLike: the GPUs of a GPU machine, not the CPU
// renderer beside them); "N,M,...": those indices, each below adapters.size() (NoAdapter
// otherwise, naming how many there are). An index may repeat: each entry is one more device
// (a second WebGPU device on the same adapter), which tests use to stand in for several GPUs.
Result<std::vector<std::size_t>> parseDeviceList(std::string_view text,
                                                 std::span<const gpu::AdapterDescription> adapters);

}  // namespace encore::app
