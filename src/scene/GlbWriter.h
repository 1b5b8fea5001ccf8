#pragma once

// Writes the documents the scene generators build as .glb bytes: a JSON chunk and one binary
// chunk, each padded to four bytes (the JSON with spaces, the binary with zeros) as glTF's
// binary container requires.

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

namespace encore::scene {

std::vector<std::uint8_t> writeGlb(const nlohmann::json& document, std::vector<std::uint8_t> binary);

}  // namespace encore::scene
