#pragma once

// Radiance .hdr files for tests that need environment panoramas on disk (encore batch
// --environment-dir): flat RGBE scanlines, which every reader accepts.

#include <filesystem>

#include <glm/glm.hpp>

namespace encore::test {

// A panorama of `width` x width / 2 pixels, `sky` radiance in its upper half and `ground` in its
// lower half, written to `path`.
void writeHdr(const std::filesystem::path& path,
              const glm::vec3& sky,
              const glm::vec3& ground,
              unsigned width = 32);

}  // namespace encore::test
