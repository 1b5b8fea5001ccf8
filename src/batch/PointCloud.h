#pragma once

// A model's surface as points (--point-cloud N, docs/batch.md#point-clouds): N points drawn
// uniformly by area from the triangles its instances draw (rest pose: no skinning or morphing),
// in the normalised frame the cameras see, each with the interpolated vertex normal and the base
// colour there (factor x vertex colour x the base colour texture at the point's texture
// coordinates, nearest texel, KHR_texture_transform ignored). Drawn from the model's seed, so the
// same seed writes the same file.

#include <cstdint>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "encore/scene/SceneData.h"

namespace encore::batch {

inline constexpr const char* kPointCloudFileName = "points.ply";

struct SurfacePoint {
    glm::vec3 position{0.0f};  // In the normalised frame.
    glm::vec3 normal{0.0f};    // Unit length (0 where the triangle's normals cancel out).
    glm::u8vec4 color{255};    // sRGB, straight alpha.
};

// `count` points of `scene`'s triangles moved by `normalization` (ViewRig.h), drawn from
// `seed` (modelSeed's). None when the scene draws no triangle of non-zero area.
std::vector<SurfacePoint> samplePointCloud(const scene::SceneData& scene,
                                           const glm::mat4& normalization,
                                           std::uint32_t count,
                                           std::uint64_t seed);

// A binary little-endian PLY of `points`: a vertex element of float x, y, z, nx, ny, nz and
// uchar red, green, blue, alpha.
std::vector<std::uint8_t> encodePly(const std::vector<SurfacePoint>& points);

}  // namespace encore::batch
