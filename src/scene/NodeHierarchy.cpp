// The node tree: world matrices, the chosen scene's instances in depth-first order (expanded by
// EXT_mesh_gpu_instancing), its placed lights and cameras, and the scene's world-space bounds.
// The file's children lists are checked to form a forest, so a malformed hierarchy cannot loop
// forever.

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "core/Log.h"
#include "scene/LoadContext.h"

namespace encore::scene {

namespace {

bool isFinite(const glm::mat3& matrix) {
    for (int c = 0; c < 3; ++c) {
        for (int r = 0; r < 3; ++r) {
            if (!std::isfinite(matrix[c][r])) {
                return false;
            }
        }
    }
    return true;
}

}  // namespace

glm::mat4 normalMatrixOf(const glm::mat4& world) {
    const glm::mat3 linear(world);
    const float determinant = glm::determinant(linear);
    if (std::abs(determinant) > 1e-30f && std::isfinite(determinant)) {
        const glm::mat3 inverseTranspose = glm::transpose(glm::inverse(linear));
        if (isFinite(inverseTranspose)) {
            return glm::mat4(inverseTranspose);
        }
    }
    // A singular matrix (a zero scale) has no inverse; the cofactor matrix is the inverse
    // transpose up to a scale and stays defined, and shaders normalise normals anyway.
    glm::mat3 cofactor;
    for (int c = 0; c < 3; ++c) {
        for (int r = 0; r < 3; ++r) {
            const int c1 = (c + 1) % 3, c2 = (c + 2) % 3, r1 = (r + 1) % 3, r2 = (r + 2) % 3;
            cofactor[c][r] = linear[c1][r1] * linear[c2][r2] - linear[c1][r2] * linear[c2][r1];
        }
    }
    // A matrix of rank one or less (two zero scales) has a zero cofactor matrix and draws
    // nothing; a non-finite one would put NaNs on the GPU. Either gets the identity.
    const bool finite = isFinite(cofactor);
    const bool zero = cofactor[0] == glm::vec3(0.0f) && cofactor[1] == glm::vec3(0.0f) &&
                      cofactor[2] == glm::vec3(0.0f);
    return finite && !zero ? glm::mat4(cofactor) : glm::mat4(1.0f);
}

glm::mat4 composeTrs(const glm::vec3& translation,
                     const glm::quat& rotation,
                     const glm::vec3& scale) {
    // The same operations, in the same order, as the loader's TRS (GltfDocument.cpp), so that a
    // node animated back to its rest pose gets bit-identical matrices.
    glm::mat4 result = glm::translate(glm::mat4(1.0f), translation);
    const float length = glm::length(rotation);
    if (length > 0.0f) {
        result *= glm::mat4_cast(rotation / length);
    }
    return glm::scale(result, scale);
}

namespace {

bool isFinite(const glm::mat4& matrix) {
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            if (!std::isfinite(matrix[c][r])) {
                return false;
            }
        }
    }
    return true;
}

Result<void> linkChildren(const GltfDocument& document, SceneData& scene) {
    const std::size_t count = document.nodes.size();
    scene.nodes.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
        const GltfNode& source = document.nodes[i];
        Node& node = scene.nodes[i];
        node.name = source.name;
        node.local = source.local;
        node.translation = source.translation;
        node.rotation = source.rotation;
        node.scale = source.scale;
        node.hasMatrix = source.hasMatrix;
        if (source.mesh) {
            node.mesh = MeshId(*source.mesh);
            node.weights = scene.meshes[*source.mesh].weights;
            if (source.skin) {
                node.skin = SkinId(*source.skin);
            }
            // Weights on a node whose mesh has no morph targets weigh nothing: ignored.
            if (source.weights && !node.weights.empty()) {
                if (source.weights->size() != node.weights.size()) {
                    return makeError(ErrorCode::InvalidFormat,
                                     "node " + std::to_string(i) + " has " +
                                         std::to_string(source.weights->size()) +
                                         " morph weights, but its mesh (" +
                                         std::to_string(*source.mesh) + ") has " +
                                         std::to_string(node.weights.size()) + " morph targets.");
                }
                node.weights = *source.weights;
            }
        }
    }
    for (std::size_t i = 0; i < count; ++i) {
        for (std::uint32_t child : document.nodes[i].children) {
            if (child == i) {
                return makeError(ErrorCode::InvalidFormat,
                                 "node " + std::to_string(i) + " lists itself as a child.");
            }
            if (scene.nodes[child].parent.valid()) {
                return makeError(ErrorCode::InvalidFormat,
                                 "node " + std::to_string(child) + " has two parents (node " +
                                     std::to_string(scene.nodes[child].parent.value) +
                                     " and node " + std::to_string(i) + ").");
            }
            scene.nodes[child].parent = NodeId(i);
            scene.nodes[i].children.push_back(NodeId(child));
        }
    }
    return {};
}

Result<void> computeWorlds(SceneData& scene) {
    std::vector<bool> done(scene.nodes.size(), false);
    std::vector<std::size_t> stack;
    for (std::size_t root = 0; root < scene.nodes.size(); ++root) {
        if (scene.nodes[root].parent.valid()) {
            continue;
        }
        stack.push_back(root);
        while (!stack.empty()) {
            const std::size_t index = stack.back();
            stack.pop_back();
            Node& node = scene.nodes[index];
            node.world = node.parent.valid() ? scene.nodes[node.parent.index()].world * node.local
                                             : node.local;
            done[index] = true;
            for (NodeId child : node.children) {
                stack.push_back(child.index());
            }
        }
    }
    // With at most one parent per node, a node no root reaches hangs off a cycle.
    for (std::size_t i = 0; i < done.size(); ++i) {
        if (!done[i]) {
            return makeError(ErrorCode::InvalidFormat,
                             "node " + std::to_string(i) +
                                 " is part of a cycle in the node hierarchy (no root reaches it).");
        }
    }
    return {};
}

// The per-instance transforms of an EXT_mesh_gpu_instancing node.
Result<std::vector<glm::mat4>> instanceTransforms(const LoadContext& context,
                                                  std::size_t node,
                                                  const GltfInstancing& instancing) {
    const SceneData& scene = context.scene;
    const std::string name = "node " + std::to_string(node) + " (EXT_mesh_gpu_instancing)";
    std::optional<std::uint32_t> count;
    std::vector<glm::vec4> values[3];
    const std::optional<std::uint32_t> accessors[3] = {instancing.translation, instancing.rotation,
                                                       instancing.scale};
    constexpr const char* kNames[3] = {"TRANSLATION", "ROTATION", "SCALE"};
    constexpr std::uint8_t kComponents[3] = {3, 4, 3};
    for (int a = 0; a < 3; ++a) {
        if (!accessors[a]) {
            continue;
        }
        const Accessor& accessor = scene.accessors[*accessors[a]];
        if (accessor.componentCount != kComponents[a]) {
            return makeError(ErrorCode::InvalidFormat,
                             name + " has a " + kNames[a] + " accessor (" +
                                 std::to_string(*accessors[a]) + ") with " +
                                 std::to_string(accessor.componentCount) + " components (needs " +
                                 std::to_string(kComponents[a]) + ").");
        }
        if (count && *count != accessor.count) {
            return makeError(ErrorCode::InvalidFormat,
                             name + " has attributes of different lengths (" + kNames[a] + " has " +
                                 std::to_string(accessor.count) + ", another has " +
                                 std::to_string(*count) + ").");
        }
        count = accessor.count;
        values[a] = scene.readFloats(AccessorId(*accessors[a]));
    }
    std::vector<glm::mat4> transforms(count.value_or(1), glm::mat4(1.0f));
    for (std::size_t i = 0; count && i < transforms.size() && i < *count; ++i) {
        glm::mat4 transform(1.0f);
        if (!values[0].empty()) {
            transform = glm::translate(transform, glm::vec3(values[0][i]));
        }
        if (!values[1].empty()) {
            const glm::vec4& r = values[1][i];
            const glm::quat rotation(r.w, r.x, r.y, r.z);
            const float length = glm::length(rotation);
            if (length > 0.0f) {
                transform *= glm::mat4_cast(rotation / length);
            }
        }
        if (!values[2].empty()) {
            transform = glm::scale(transform, glm::vec3(values[2][i]));
        }
        transforms[i] = transform;
    }
    return transforms;
}

// A light shines along its node's -Z axis; scale and shear only move where that axis points.
LightInstance placeLight(std::uint32_t light, std::size_t node, const glm::mat4& world) {
    LightInstance placed;
    placed.light = LightId(light);
    placed.node = NodeId(node);
    placed.position = glm::vec3(world[3]);
    const glm::vec3 direction = glm::vec3(world * glm::vec4(0.0f, 0.0f, -1.0f, 0.0f));
    const float length = glm::length(direction);
    if (length > 0.0f && std::isfinite(length)) {
        placed.direction = direction / length;
    }
    return placed;
}

// glTF ignores a camera node's scale: the rotation is orthonormalised (Gram-Schmidt from the
// view axis, then the up axis, so where the camera looks is kept exactly) and the translation
// kept. A degenerate matrix keeps the identity rotation.
glm::mat4 cameraWorld(const glm::mat4& world) {
    glm::mat4 result(1.0f);
    result[3] = glm::vec4(glm::vec3(world[3]), 1.0f);
    const glm::vec3 axisZ(world[2]);
    const float lengthZ = glm::length(axisZ);
    if (!(lengthZ > 1e-12f) || !std::isfinite(lengthZ)) {
        return result;
    }
    const glm::vec3 z = axisZ / lengthZ;
    const glm::vec3 axisY = glm::vec3(world[1]) - glm::dot(glm::vec3(world[1]), z) * z;
    const float lengthY = glm::length(axisY);
    if (!(lengthY > 1e-12f) || !std::isfinite(lengthY)) {
        return result;
    }
    const glm::vec3 y = axisY / lengthY;
    // A mirrored node would flip x; the camera keeps a right-handed frame regardless.
    const glm::vec3 x = glm::cross(y, z);
    result[0] = glm::vec4(x, 0.0f);
    result[1] = glm::vec4(y, 0.0f);
    result[2] = glm::vec4(z, 0.0f);
    return result;
}

std::vector<std::uint32_t> sceneRoots(const GltfDocument& document, const SceneData& scene) {
    if (document.scene) {
        return document.scenes[*document.scene];
    }
    if (!document.scenes.empty()) {
        return document.scenes[0];
    }
    std::vector<std::uint32_t> roots;  // No scenes at all: draw every root node.
    for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
        if (!scene.nodes[i].parent.valid()) {
            roots.push_back(static_cast<std::uint32_t>(i));
        }
    }
    return roots;
}

}  // namespace

Result<void> buildNodes(LoadContext& context) {
    SceneData& scene = context.scene;
    ENCORE_TRY(linkChildren(context.document, scene));
    ENCORE_TRY(computeWorlds(scene));
    scene.lights = context.document.lights;
    scene.cameras = context.document.cameras;

    std::vector<Bounds> meshBounds(scene.meshes.size());
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        for (const Primitive& primitive : scene.meshes[m].primitives) {
            meshBounds[m].extend(primitive.bounds);
        }
    }
    const auto roots = sceneRoots(context.document, scene);
    std::vector<std::size_t> stack(roots.rbegin(), roots.rend());
    while (!stack.empty()) {
        const std::size_t index = stack.back();
        stack.pop_back();
        const Node& node = scene.nodes[index];
        for (auto child = node.children.rbegin(); child != node.children.rend(); ++child) {
            stack.push_back(child->index());
        }
        const GltfNode& source = context.document.nodes[index];
        if (source.light) {
            scene.lightInstances.push_back(placeLight(*source.light, index, node.world));
        }
        if (source.camera) {
            scene.cameraInstances.push_back(
                {CameraId(*source.camera), NodeId(index), cameraWorld(node.world)});
        }
        if (!node.mesh) {
            continue;
        }
        std::vector<glm::mat4> transforms{glm::mat4(1.0f)};
        if (const auto& instancing = source.instancing) {
            ENCORE_TRY_ASSIGN(transforms, instanceTransforms(context, index, *instancing));
        }
        for (std::size_t t = 0; t < transforms.size(); ++t) {
            Instance instance;
            instance.mesh = *node.mesh;
            instance.node = NodeId(index);
            instance.world = node.world * transforms[t];
            instance.instanceTransform = transforms[t];
            if (!isFinite(instance.world)) {
                // NaN or infinite matrices, TRS values or instance transforms: nothing sensible
                // can be drawn, and the scene's bounds and framing must stay finite.
                const std::string which =
                    source.instancing ? " (instance " + std::to_string(t) + ")" : "";
                ENCORE_TRY(context.warn(ErrorCode::InvalidFormat,
                                        "node " + std::to_string(index) + which +
                                            " has a world transform with values that are not "
                                            "finite (NaN or infinity); its mesh (" +
                                            std::to_string(node.mesh->index()) +
                                            ") is not drawn there."));
                continue;
            }
            instance.normalMatrix = normalMatrixOf(instance.world);
            scene.bounds.extend(meshBounds[node.mesh->index()].transformed(instance.world));
            scene.instances.push_back(instance);
        }
    }
    if (scene.instances.empty()) {
        // Valid glTF (a scene may have no nodes, nodes no meshes), so not an error even with
        // --strict: the renderer draws the background alone.
        std::string why;
        if (context.document.scenes.empty() && scene.nodes.empty()) {
            why = "the asset has no scenes and no nodes";
        } else if (roots.empty()) {
            why = "the scene it shows has no nodes";
        } else {
            why = "no node of the scene it shows has a mesh that can be drawn";
        }
        std::string warning = context.displayName + ": The asset draws nothing (" + why +
                              "); the image shows the background only.";
        logWarning(warning);
        scene.warnings.push_back(std::move(warning));
    }
    return {};
}

}  // namespace encore::scene
