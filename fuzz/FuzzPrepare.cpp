// libFuzzer target: load, then do everything CPU-side that src/render does with an accepted
// scene before it touches the GPU, checking the promises of SceneData.h on the way
// (loadAndPrepare, PrepareChecks.cpp). Inputs the loader rejects end there as in the load
// target.

#include <cstddef>
#include <cstdint>

#include "FuzzCommon.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    encore::fuzz::loadAndPrepare(data, size);
    return 0;
}
