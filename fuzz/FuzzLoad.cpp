// libFuzzer target: the glTF loader from memory (JSON .gltf or binary .glb, chosen by the GLB
// magic), with image decoding. Any crash, sanitizer report, leak or hang is a finding; errors
// returned by the loader are the expected outcome for most inputs.

#include <cstddef>
#include <cstdint>

#include "FuzzCommon.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    auto scene = encore::fuzz::loadFuzzInput(data, size);
    if (!scene) {
        ENCORE_FUZZ_CHECK(!scene.error().message.empty());
    }
    return 0;
}
