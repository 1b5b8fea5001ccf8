// libFuzzer target: the body of encore_fuzz_prepare (loadAndPrepare: load, then the CPU-side
// promises of SceneData.h) on inputs mutated structurally (NumberMutator.h): a few numbers of a
// valid glTF or GLB set to boundary values. Inputs the number mutator leaves alone (one in
// sixteen, and those that do not parse) get libFuzzer's byte-level LLVMFuzzerMutate.
// LLVMFuzzerCustomCrossOver copies numbers of one document into the same places of another.

#include <cstddef>
#include <cstdint>

#include "FuzzCommon.h"
#include "NumberMutator.h"

extern "C" std::size_t LLVMFuzzerMutate(std::uint8_t* data, std::size_t size, std::size_t maxSize);

extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data,
                                               std::size_t size,
                                               std::size_t maxSize,
                                               unsigned int seed) {
    const std::size_t mutated = encore::fuzz::mutateNumbers(data, size, maxSize, seed);
    return mutated != 0 ? mutated : LLVMFuzzerMutate(data, size, maxSize);
}

extern "C" std::size_t LLVMFuzzerCustomCrossOver(const std::uint8_t* data1,
                                                 std::size_t size1,
                                                 const std::uint8_t* data2,
                                                 std::size_t size2,
                                                 std::uint8_t* out,
                                                 std::size_t maxOutSize,
                                                 unsigned int seed) {
    return encore::fuzz::crossOverNumbers(data1, size1, data2, size2, out, maxOutSize, seed);
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    encore::fuzz::loadAndPrepare(data, size);
    return 0;
}
