#include "render/culling/CullingBounds.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "render/AnimationBuffers.h"

namespace encore::render {

namespace {

// Never culled: passes every plane wherever its centre is (a negative skin weight moves a
// vertex outside the hull of its joints).
constexpr glm::vec4 kUnboundedSphere{0.0f, 0.0f, 0.0f, 1e30f};

glm::vec4 sphereOf(const scene::Bounds& bounds) {
    return bounds.empty() ? glm::vec4(0.0f) : glm::vec4(bounds.center(), bounds.radius());
}

float largestAxisScale(const glm::mat4& m) {
    return std::sqrt(std::max({glm::dot(glm::vec3(m[0]), glm::vec3(m[0])),
                               glm::dot(glm::vec3(m[1]), glm::vec3(m[1])),
                               glm::dot(glm::vec3(m[2]), glm::vec3(m[2]))}));
}

struct MeshJointSpheres {
    std::uint32_t first = 0;
    std::uint32_t count = 0;
    bool negativeWeight = false;
};

// The spheres around the vertices each joint influences, over the primitives drawn skinned.
MeshJointSpheres appendJointSpheres(const scene::SceneData& scene,
                                    scene::MeshId meshId,
                                    const AnimationBuffers& animation,
                                    std::vector<glm::vec4>& spheres) {
    MeshJointSpheres result;
    std::vector<scene::Bounds> joints;
    const scene::Mesh& mesh = scene.meshes[meshId.index()];
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
        if (!animation.skinnedPrimitive(meshId, p)) {
            continue;
        }
        const scene::Primitive& primitive = mesh.primitives[p];
        const auto positions = scene.readFloats(*primitive.attribute(scene::Semantic::Position));
        const std::pair<scene::Semantic, scene::Semantic> sets[2] = {
            {scene::Semantic::Joints0, scene::Semantic::Weights0},
            {scene::Semantic::Joints1, scene::Semantic::Weights1}};
        for (const auto& [jointSemantic, weightSemantic] : sets) {
            const auto jointAccessor = primitive.attribute(jointSemantic);
            const auto weightAccessor = primitive.attribute(weightSemantic);
            if (!jointAccessor || !weightAccessor) {
                continue;  // The vertex shader reads JOINTS_1 only with WEIGHTS_1.
            }
            const auto indices = scene.readFloats(*jointAccessor);
            const auto weights = scene.readFloats(*weightAccessor);
            const std::size_t count = std::min({positions.size(), indices.size(), weights.size()});
            for (std::size_t v = 0; v < count; ++v) {
                for (int k = 0; k < 4; ++k) {
                    if (weights[v][k] < 0.0f) {
                        result.negativeWeight = true;
                    }
                    if (!(weights[v][k] > 0.0f)) {
                        continue;
                    }
                    const auto joint = static_cast<std::size_t>(indices[v][k]);
                    if (joint >= joints.size()) {
                        joints.resize(joint + 1);
                    }
                    joints[joint].extend(glm::vec3(positions[v]));
                }
            }
        }
    }
    result.first = static_cast<std::uint32_t>(spheres.size());
    result.count = static_cast<std::uint32_t>(joints.size());
    for (const scene::Bounds& bounds : joints) {
        spheres.push_back(bounds.empty() ? glm::vec4(0.0f, 0.0f, 0.0f, -1.0f) : sphereOf(bounds));
    }
    return result;
}

// Each target's largest position delta over the mesh's primitives; returns the first one's
// float index.
std::uint32_t appendMorphExtents(const scene::SceneData& scene,
                                 const scene::Mesh& mesh,
                                 std::vector<glm::vec4>& shapes) {
    std::vector<float> extents(mesh.weights.size(), 0.0f);
    for (const scene::Primitive& primitive : mesh.primitives) {
        for (std::size_t t = 0; t < primitive.targets.size() && t < mesh.weights.size(); ++t) {
            if (!primitive.targets[t].position) {
                continue;
            }
            float& extent = extents[t];
            for (const glm::vec4& delta : scene.readFloats(*primitive.targets[t].position)) {
                const float length = glm::length(glm::vec3(delta));
                // A non-finite delta puts the vertex anywhere.
                extent = std::isfinite(length) ? std::max(extent, length) : 1e30f;
            }
        }
    }
    const auto first = static_cast<std::uint32_t>(shapes.size() * 4);
    for (std::size_t t = 0; t < extents.size(); t += 4) {
        glm::vec4 packed(0.0f);
        for (std::size_t c = 0; c < 4 && t + c < extents.size(); ++c) {
            packed[static_cast<int>(c)] = extents[t + c];
        }
        shapes.push_back(packed);
    }
    return first;
}

Sphere moved(const glm::mat4& transform, const glm::vec4& sphere, float growth) {
    return Sphere(glm::vec3(transform * glm::vec4(glm::vec3(sphere), 1.0f)),
                  (sphere.w + growth) * largestAxisScale(transform));
}

}  // namespace

CullingBounds CullingBounds::build(const scene::SceneData& scene,
                                   std::span<const std::size_t> instanceAt,
                                   const AnimationBuffers* animation) {
    CullingBounds bounds;
    bounds.slots.resize(instanceAt.size());
    std::vector<std::optional<MeshJointSpheres>> jointSpheresOfMesh(scene.meshes.size());
    std::vector<std::optional<std::uint32_t>> morphExtentsOfMesh(scene.meshes.size());
    for (std::size_t slot = 0; slot < instanceAt.size(); ++slot) {
        const std::size_t sceneInstance = instanceAt[slot];
        const scene::Instance& instance = scene.instances[sceneInstance];
        const scene::Mesh& mesh = scene.meshes[instance.mesh.index()];
        const glm::uvec2 offsets =
            animation ? animation->instanceOffsets(sceneInstance) : glm::uvec2(SlotBounds::kNone);
        SlotBounds& record = bounds.slots[slot];

        const bool skinned = offsets.x != SlotBounds::kNone;
        scene::Bounds rigid;
        bool anyRigid = false;
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            if (!skinned || !animation->skinnedPrimitive(instance.mesh, p)) {
                rigid.extend(mesh.primitives[p].bounds);
                anyRigid = true;
            }
        }
        if (anyRigid) {
            record.rigidSphere = sphereOf(rigid);
        }
        if (skinned) {
            auto& joints = jointSpheresOfMesh[instance.mesh.index()];
            if (!joints) {
                joints = appendJointSpheres(scene, instance.mesh, *animation, bounds.shapes);
            }
            if (joints->negativeWeight) {
                record.rigidSphere = kUnboundedSphere;
            } else {
                record.firstJointSphere = joints->first;
                record.jointCount = joints->count;
                record.jointOffset = offsets.x;
            }
        }
        if (offsets.y != SlotBounds::kNone && !mesh.weights.empty()) {
            auto& extents = morphExtentsOfMesh[instance.mesh.index()];
            if (!extents) {
                extents = appendMorphExtents(scene, mesh, bounds.shapes);
            }
            record.firstMorphExtent = *extents;
            record.morphCount = static_cast<std::uint32_t>(mesh.weights.size());
            record.weightOffset = offsets.y;
        }
    }
    return bounds;
}

std::vector<Sphere> CullingBounds::worldSpheres(std::uint32_t slot,
                                                const glm::mat4& world,
                                                std::span<const glm::mat4> joints,
                                                std::span<const float> weights) const {
    const SlotBounds& record = slots[slot];
    float growth = 0.0f;
    for (std::uint32_t t = 0; t < record.morphCount; ++t) {
        const std::uint32_t extent = record.firstMorphExtent + t;
        growth += std::abs(weights[record.weightOffset + t]) *
                  shapes[extent / 4][static_cast<int>(extent % 4)];
    }
    std::vector<Sphere> spheres;
    if (record.rigidSphere.w >= 0.0f) {
        spheres.push_back(moved(world, record.rigidSphere, growth));
    }
    for (std::uint32_t j = 0; j < record.jointCount; ++j) {
        const glm::vec4& sphere = shapes[record.firstJointSphere + j];
        if (sphere.w >= 0.0f) {
            spheres.push_back(moved(joints[record.jointOffset + j], sphere, growth));
        }
    }
    return spheres;
}

bool hullIntersects(const Frustum& frustum, std::span<const Sphere> spheres) {
    for (const glm::vec4& plane : frustum.planes) {
        bool allOutside = true;
        for (const Sphere& sphere : spheres) {
            if (glm::dot(glm::vec3(plane), glm::vec3(sphere)) + plane.w >= -sphere.w) {
                allOutside = false;
                break;
            }
        }
        if (allOutside) {
            return false;
        }
    }
    return true;
}

}  // namespace encore::render
