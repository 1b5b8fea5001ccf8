#include "trace/TraceScene.h"

#include <cmath>
#include <optional>

#include "scene/TriangleCorners.h"

namespace encore::trace {
namespace {

bool finite(const glm::vec4& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

bool finite(const glm::vec3& v) {
    return finite(glm::vec4(v, 0.0f));
}

// Appends a primitive's hierarchy and triangles; its root's index, or none when it has no
// triangle with a box (points, lines, only non-finite positions).
Result<std::optional<std::uint32_t>> addPrimitive(const scene::SceneData& scene,
                                                  const scene::Primitive& primitive,
                                                  const BvhBuilder& builder,
                                                  const BvhBuildOptions& options,
                                                  TraceScene& trace) {
    const auto position = primitive.attribute(scene::Semantic::Position);
    if (!position) {
        return std::optional<std::uint32_t>();
    }
    const std::vector<glm::vec4> positions = scene.readFloats(*position);
    const std::vector<std::uint32_t> corners = scene::triangleCorners(scene, primitive);
    std::vector<TraceTriangle> triangles(corners.size() / 3);
    std::vector<scene::Bounds> boxes(triangles.size());
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        TraceTriangle& triangle = triangles[t];
        triangle.a = glm::vec3(positions[corners[3 * t]]);
        triangle.b = glm::vec3(positions[corners[3 * t + 1]]);
        triangle.c = glm::vec3(positions[corners[3 * t + 2]]);
        triangle.index = std::uint32_t(t);
        // A triangle with a non-finite corner is left out: it cannot be intersected reliably.
        if (finite(triangle.a) && finite(triangle.b) && finite(triangle.c)) {
            boxes[t].extend(triangle.a);
            boxes[t].extend(triangle.b);
            boxes[t].extend(triangle.c);
        }
    }
    ENCORE_TRY_ASSIGN(Bvh bvh, builder.build(boxes, options));
    if (bvh.nodes.empty()) {
        return std::optional<std::uint32_t>();
    }
    const auto nodeBase = std::uint32_t(trace.meshNodes.size());
    const auto triangleBase = std::uint32_t(trace.triangles.size());
    for (BvhNode node : bvh.nodes) {
        node.first += node.leaf() ? triangleBase : nodeBase;
        trace.meshNodes.push_back(node);
    }
    for (const std::uint32_t item : bvh.items) {
        trace.triangles.push_back(triangles[item]);
    }
    return std::optional<std::uint32_t>(nodeBase);
}

}  // namespace

Result<TraceScene> buildTraceScene(const scene::SceneData& scene,
                                   const BvhBuilder& builder,
                                   const BvhBuildOptions& options) {
    TraceScene trace;
    // Each primitive's root (none: not traced), in the meshes' order, and the first primitive
    // of each mesh in that order.
    std::vector<std::optional<std::uint32_t>> roots;
    std::vector<std::uint32_t> firstPrimitive;
    for (const scene::Mesh& mesh : scene.meshes) {
        firstPrimitive.push_back(std::uint32_t(roots.size()));
        for (const scene::Primitive& primitive : mesh.primitives) {
            ENCORE_TRY_ASSIGN(auto root, addPrimitive(scene, primitive, builder, options, trace));
            roots.push_back(root);
        }
    }
    std::vector<TraceObject> objects;
    std::vector<scene::Bounds> boxes;
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const scene::Instance& instance = scene.instances[i];
        const scene::Mesh& mesh = scene.meshes[instance.mesh.index()];
        const glm::mat4 worldToObject = glm::inverse(instance.world);
        if (!finite(worldToObject[0]) || !finite(worldToObject[1]) || !finite(worldToObject[2]) ||
            !finite(worldToObject[3])) {
            continue;  // A zero scale: the instance has no surface to hit.
        }
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            const std::uint32_t primitive =
                firstPrimitive[instance.mesh.index()] + std::uint32_t(p);
            if (!roots[primitive]) {
                continue;
            }
            const BvhNode& root = trace.meshNodes[*roots[primitive]];
            objects.push_back(TraceObject{worldToObject, *roots[primitive], std::uint32_t(i),
                                          primitive,
                                          std::uint32_t(mesh.primitives[p].material.index())});
            boxes.push_back(scene::Bounds{root.min, root.max}.transformed(instance.world));
        }
    }
    ENCORE_TRY_ASSIGN(Bvh top, builder.build(boxes, options));
    trace.objectNodes = std::move(top.nodes);
    trace.objects.reserve(top.items.size());
    for (const std::uint32_t item : top.items) {
        trace.objects.push_back(objects[item]);
    }
    return trace;
}

}  // namespace encore::trace
