#include "scene/GlbWriter.h"

#include <cstring>
#include <string>

namespace encore::scene {

namespace {

void appendChunk(std::vector<std::uint8_t>& glb,
                 std::uint32_t type,
                 std::vector<std::uint8_t> data,
                 std::uint8_t padding) {
    while (data.size() % 4 != 0) {
        data.push_back(padding);
    }
    const std::uint32_t header[2] = {static_cast<std::uint32_t>(data.size()), type};
    const auto* headerBytes = reinterpret_cast<const std::uint8_t*>(header);
    glb.insert(glb.end(), headerBytes, headerBytes + sizeof(header));
    glb.insert(glb.end(), data.begin(), data.end());
}

}  // namespace

std::size_t GlbBinaryChunk::addView(nlohmann::json& document,
                                    std::span<const std::uint8_t> bytes,
                                    std::optional<int> target) {
    while (mBytes.size() % 4 != 0) {
        mBytes.push_back(0);
    }
    const std::size_t offset = mBytes.size();
    mBytes.insert(mBytes.end(), bytes.begin(), bytes.end());
    nlohmann::json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes.size()}};
    if (target) {
        view["target"] = *target;
    }
    document["bufferViews"].push_back(std::move(view));
    return document["bufferViews"].size() - 1;
}

std::size_t GlbBinaryChunk::addPng(nlohmann::json& document, std::span<const std::uint8_t> png) {
    const std::size_t view = addView(document, png);
    document["images"].push_back({{"bufferView", view}, {"mimeType", "image/png"}});
    return document["images"].size() - 1;
}

std::vector<std::uint8_t> writeGlb(const nlohmann::json& document,
                                   std::vector<std::uint8_t> binary) {
    constexpr std::uint32_t kJsonChunk = 0x4E4F534A;
    constexpr std::uint32_t kBinaryChunk = 0x004E4942;
    const std::string text = document.dump();
    std::vector<std::uint8_t> glb = {'g', 'l', 'T', 'F', 2, 0, 0, 0, 0, 0, 0, 0};
    appendChunk(glb, kJsonChunk, std::vector<std::uint8_t>(text.begin(), text.end()), ' ');
    appendChunk(glb, kBinaryChunk, std::move(binary), 0);
    const std::uint32_t total = static_cast<std::uint32_t>(glb.size());
    std::memcpy(&glb[8], &total, sizeof(total));
    return glb;
}

}  // namespace encore::scene
