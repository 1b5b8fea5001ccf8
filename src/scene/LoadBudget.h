#pragma once

// A memory budget shared by loads that run at once (LoadOptions::budget): each load tells it
// what its scene holds decoded whenever the loader checks LoadOptions::maxModelBytes (after the
// buffers, the decoded data and each image), and may be held there until the others leave room.
// encore batch shares its --memory-limit so, between the scenes loaded ahead and the loads in
// progress: a collection of decompression bombs cannot take a multiple of it.

#include <cstdint>

#include "encore/core/Result.h"

namespace encore::scene {

class LoadBudget {
  public:
    virtual ~LoadBudget() = default;
    // The load now holds `bytes` decoded. Returns once it may go on (perhaps after waiting for
    // other loads); an error fails the load.
    virtual Result<void> holding(std::uint64_t bytes) = 0;
};

}  // namespace encore::scene
