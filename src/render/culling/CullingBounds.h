#pragma once

// What GPU culling needs to bound each instance wherever animation puts it, in object space, so
// that the culling pass can follow every frame's transforms from the buffers the vertex shader
// reads (no CPU update per moved instance, and the same for animation on the CPU and the GPU):
//  - a rigid part: the sphere of the primitives drawn with the instance's world matrix, moved by
//    the world matrix in the InstanceBuffer;
//  - for a skinned instance, one sphere per joint around the vertices that joint influences (in
//    bind-pose mesh space), moved by the joint's matrix. A skinned vertex is a convex
//    combination of its joints' transforms of it (the vertex shader's weighted sum, divided by
//    the weight sum at the perspective divide), so it lies in the convex hull of the moved
//    joint spheres; that hull is outside a frustum plane exactly when every sphere is;
//  - for a morphed instance, each target's largest position delta: every sphere grows by the
//    sum over targets of |weight| times that delta, read from the current weights.
// A primitive with a negative skin weight leaves the hull; its instance is never culled.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "encore/scene/SceneData.h"
#include "render/culling/Frustum.h"

namespace encore::render {

class AnimationBuffers;

// One instance slot's record, as culling.wgsl reads it (48 bytes).
struct SlotBounds {
    static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
    glm::vec4 rigidSphere{0.0f, 0.0f, 0.0f, -1.0f};  // Object space; radius < 0: no rigid part.
    std::uint32_t firstJointSphere = 0;              // Into CullingBounds::shapes.
    std::uint32_t jointCount = 0;                    // 0: not skinned.
    std::uint32_t jointOffset = kNone;               // The instance's first joint matrix.
    std::uint32_t firstMorphExtent = 0;              // In floats: component 4i + c is shapes[i][c].
    std::uint32_t morphCount = 0;                    // 0: not morphed.
    std::uint32_t weightOffset = kNone;              // The instance's first morph weight.
    std::uint32_t firstDraw = 0;  // Set by GpuCuller: the culled draws of the slot's mesh.
    std::uint32_t drawCount = 0;
};
static_assert(sizeof(SlotBounds) == 48);

struct CullingBounds {
    std::vector<SlotBounds> slots;  // InstanceBuffer slot order.
    // One array, so the culling pass stays within WebGPU's default 8 storage buffers: per
    // skinned mesh its joint spheres (radius < 0: the joint moves no vertex), per morphed mesh
    // its targets' largest deltas, four to a vec4.
    std::vector<glm::vec4> shapes;

    // `instanceAt[slot]` is the scene instance in that slot; `animation` is null when the scene
    // has no skinned or morphed primitive.
    static CullingBounds build(const scene::SceneData& scene,
                               std::span<const std::size_t> instanceAt,
                               const AnimationBuffers* animation);

    // The world-space spheres whose convex hull bounds the slot's geometry, given the slot's
    // world matrix and the current joint matrices and morph weights (as culling.wgsl computes
    // them; for tests and CPU checks).
    std::vector<Sphere> worldSpheres(std::uint32_t slot,
                                     const glm::mat4& world,
                                     std::span<const glm::mat4> joints,
                                     std::span<const float> weights) const;
};

// True unless every sphere lies outside one plane of the frustum: the hull test.
bool hullIntersects(const Frustum& frustum, std::span<const Sphere> spheres);

}  // namespace encore::render
