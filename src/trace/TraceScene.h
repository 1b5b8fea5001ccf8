#pragma once

// A scene's triangles as a ray tracer reads them: two levels of bounding volume hierarchies
// (Bvh.h), in arrays that go to the GPU as they are.
//
// - One hierarchy per triangle primitive of a mesh, over its triangles in object space (the
//   bottom level): shared by every instance of the mesh.
// - One over the objects (the top level): an object is one primitive of one instance, with the
//   matrix that takes world-space rays into its object space and the root of its primitive's
//   hierarchy.
//
// Points and lines are not traced. Positions are the primitive's own (no skinning or morphing);
// the instances' world matrices are those SceneData holds.

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "encore/core/Result.h"
#include "encore/scene/SceneData.h"
#include "trace/Bvh.h"

namespace encore::trace {

// A triangle's corners in its primitive's object space, 48 bytes as the GPU reads them.
struct TraceTriangle {
    glm::vec3 a{0.0f};
    std::uint32_t index = 0;  // The triangle's index in its primitive (its attributes' order).
    glm::vec3 b{0.0f};
    std::uint32_t padding0 = 0;
    glm::vec3 c{0.0f};
    std::uint32_t padding1 = 0;
};
static_assert(sizeof(TraceTriangle) == 48);

// One primitive of one instance, 80 bytes.
struct TraceObject {
    glm::mat4 worldToObject{1.0f};
    std::uint32_t root = 0;       // Its primitive's root in TraceScene::meshNodes.
    std::uint32_t instance = 0;   // In SceneData::instances.
    std::uint32_t primitive = 0;  // Counted over the meshes' primitives in order.
    std::uint32_t material = 0;   // The primitive's default material.
};
static_assert(sizeof(TraceObject) == 80);

struct TraceScene {
    // Every primitive's hierarchy, one after another: an interior node's `first` and a leaf's
    // (an index into `triangles`) are absolute.
    std::vector<BvhNode> meshNodes;
    std::vector<TraceTriangle> triangles;  // In leaf order.
    std::vector<BvhNode> objectNodes;      // The top level; a leaf's range indexes `objects`.
    std::vector<TraceObject> objects;      // In leaf order.

    std::uint64_t bytes() const {
        return (meshNodes.size() + objectNodes.size()) * sizeof(BvhNode) +
               triangles.size() * sizeof(TraceTriangle) + objects.size() * sizeof(TraceObject);
    }
};

Result<TraceScene> buildTraceScene(const scene::SceneData& scene,
                                   const BvhBuilder& builder,
                                   const BvhBuildOptions& options = {});

}  // namespace encore::trace
