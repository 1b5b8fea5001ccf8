#pragma once

// A memory budget shared by loads that run at once (LoadOptions::budget): each load tells it
// what its scene holds decoded whenever the loader checks LoadOptions::maxModelBytes (after the
// buffers, the decoded data and each image), and may be held there until the others leave room.
// encore batch shares its --memory-limit so, between the scenes loaded ahead and the loads in
// progress: a collection of decompression bombs cannot take a multiple of it.

#include <cstdint>

#include "encore/core/Result.h"
#include "encore/scene/SceneData.h"

namespace encore::scene {

// The bytes a scene holds decoded, as a budget counts them (and LoadOptions::maxModelBytes
// bounds them): its buffers, decompressed and materialised data among them, and its decoded
// images.
inline std::uint64_t decodedBytes(const SceneData& scene) {
    std::uint64_t bytes = 0;
    for (const Buffer& buffer : scene.buffers) {
        bytes += buffer.bytes.size();
    }
    for (const Image& image : scene.images) {
        bytes += image.rgba8.size();
    }
    return bytes;
}

class LoadBudget {
  public:
    virtual ~LoadBudget() = default;
    // The load now holds `bytes` decoded. Returns once it may go on (perhaps after waiting for
    // other loads); an error fails the load.
    virtual Result<void> holding(std::uint64_t bytes) = 0;
};

}  // namespace encore::scene
