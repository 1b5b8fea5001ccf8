#pragma once

// Writes the documents the scene generators build as .glb bytes: the binary chunk with the
// bufferViews and accessors that describe it, then the container, a JSON chunk and the binary
// chunk, each padded to four bytes (the JSON with spaces, the binary with zeros) as glTF's
// binary container requires.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <nlohmann/json.hpp>

namespace encore::scene {

// The binary chunk of a generated .glb (buffer 0), filled view by view.
class GlbBinaryChunk {
  public:
    // Appends `bytes`, 4-byte aligned, as a bufferView with `target` when given; returns its
    // index.
    std::size_t addView(nlohmann::json& document,
                        std::span<const std::uint8_t> bytes,
                        std::optional<int> target = std::nullopt);

    // Appends `values` as a bufferView and an accessor of `count` elements of `type`, with
    // `bounds` ([min, max]) when it is not null; returns the accessor's index.
    template <typename T>
    std::size_t addAccessor(nlohmann::json& document,
                            const std::vector<T>& values,
                            int componentType,
                            const char* type,
                            std::size_t count,
                            std::optional<int> target = std::nullopt,
                            const nlohmann::json& bounds = nullptr) {
        const std::size_t view =
            addView(document,
                    std::span(reinterpret_cast<const std::uint8_t*>(values.data()),
                              values.size() * sizeof(T)),
                    target);
        nlohmann::json accessor = {{"bufferView", view},
                                   {"componentType", componentType},
                                   {"count", count},
                                   {"type", type}};
        if (!bounds.is_null()) {
            accessor["min"] = bounds[0];
            accessor["max"] = bounds[1];
        }
        document["accessors"].push_back(std::move(accessor));
        return document["accessors"].size() - 1;
    }

    // Appends an encoded PNG as a bufferView and an image; returns the image's index.
    std::size_t addPng(nlohmann::json& document, std::span<const std::uint8_t> png);

    std::size_t size() const { return mBytes.size(); }
    std::vector<std::uint8_t> take() { return std::move(mBytes); }

  private:
    std::vector<std::uint8_t> mBytes;
};

std::vector<std::uint8_t> writeGlb(const nlohmann::json& document,
                                   std::vector<std::uint8_t> binary);

}  // namespace encore::scene
