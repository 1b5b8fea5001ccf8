#include "scene/TriangleCorners.h"

namespace encore::scene {

std::vector<std::uint32_t> triangleCorners(const SceneData& scene, const Primitive& primitive) {
    std::vector<std::uint32_t> indices;
    if (primitive.indices) {
        indices = scene.readIndices(*primitive.indices);
    } else {
        indices.resize(primitive.vertexCount);
        for (std::uint32_t i = 0; i < primitive.vertexCount; ++i) {
            indices[i] = i;
        }
    }
    if (primitive.topology == Topology::TriangleList) {
        indices.resize(indices.size() / 3 * 3);
        return indices;
    }
    std::vector<std::uint32_t> corners;
    if (primitive.topology == Topology::TriangleStrip) {
        for (std::size_t i = 2; i < indices.size(); ++i) {
            // Every other triangle of a strip is wound the other way round.
            const bool odd = i % 2 == 1;
            corners.insert(corners.end(),
                           {indices[i - 2], indices[odd ? i : i - 1], indices[odd ? i - 1 : i]});
        }
    }
    return corners;
}

}  // namespace encore::scene
