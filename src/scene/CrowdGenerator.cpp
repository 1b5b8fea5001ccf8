// The animated crowd of CrowdGenerator.h. The character: a square column 0.3 wide and 2 tall
// in four segments, joint j at height 0.5 j, each ring of vertices weighed between the joints
// below and above it, so the column bends smoothly when the joints turn.

#include "scene/CrowdGenerator.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "scene/GlbWriter.h"

namespace encore::scene {

namespace {

using json = nlohmann::json;

constexpr int kFloat = 5126;
constexpr int kUnsignedByte = 5121;
constexpr int kUnsignedShort = 5123;
constexpr float kSegment = 0.5f;
constexpr std::uint32_t kRings = 2 * kCrowdJointsPerCharacter + 1;  // Two rings per segment.

// The column: per ring four corners (each twice, with the normals of its two faces).
json addCharacterMesh(json& document, GlbBinaryChunk& binary) {
    std::vector<float> positions, normals, weights;
    std::vector<std::uint8_t> joints;
    std::vector<std::uint16_t> indices;
    const float h = 0.15f;
    const glm::vec2 corners[4] = {{-h, -h}, {h, -h}, {h, h}, {-h, h}};
    const float height = kSegment * float(kCrowdJointsPerCharacter);
    for (std::uint32_t ring = 0; ring < kRings; ++ring) {
        const float y = height * float(ring) / float(kRings - 1);
        // Between joint `below` (at kSegment * below) and the next one.
        const float along = y / kSegment;
        const auto below = static_cast<std::uint32_t>(
            std::min<float>(std::floor(along), float(kCrowdJointsPerCharacter - 1)));
        const float upper = std::clamp(along - float(below), 0.0f, 1.0f) * 0.5f;
        const std::uint32_t above = std::min(below + 1, kCrowdJointsPerCharacter - 1);
        for (int face = 0; face < 4; ++face) {
            const glm::vec2 a = corners[face];
            const glm::vec2 b = corners[(face + 1) % 4];
            const glm::vec2 outward = glm::normalize(a + b);
            for (const glm::vec2& corner : {a, b}) {
                positions.insert(positions.end(), {corner.x, y, corner.y});
                normals.insert(normals.end(), {outward.x, 0.0f, outward.y});
                joints.insert(joints.end(), {std::uint8_t(below), std::uint8_t(above), 0, 0});
                weights.insert(weights.end(), {1.0f - upper, upper, 0.0f, 0.0f});
            }
        }
    }
    for (std::uint32_t ring = 0; ring + 1 < kRings; ++ring) {
        for (std::uint16_t face = 0; face < 4; ++face) {
            const auto v0 = std::uint16_t(ring * 8 + face * 2);
            const auto v2 = std::uint16_t(v0 + 8);
            indices.insert(indices.end(), {v0, std::uint16_t(v0 + 1), std::uint16_t(v2 + 1), v0,
                                           std::uint16_t(v2 + 1), v2});
        }
    }
    const std::size_t vertices = positions.size() / 3;
    const json bounds = {{-h, 0.0f, -h}, {h, height, h}};
    json attributes = {
        {"POSITION",
         binary.addAccessor(document, positions, kFloat, "VEC3", vertices, std::nullopt, bounds)},
        {"NORMAL", binary.addAccessor(document, normals, kFloat, "VEC3", vertices)},
        {"JOINTS_0", binary.addAccessor(document, joints, kUnsignedByte, "VEC4", vertices)},
        {"WEIGHTS_0", binary.addAccessor(document, weights, kFloat, "VEC4", vertices)}};
    const std::size_t indexAccessor =
        binary.addAccessor(document, indices, kUnsignedShort, "SCALAR", indices.size());
    return {{"name", "character"},
            {"primitives",
             {{{"attributes", attributes}, {"indices", indexAccessor}, {"material", 0}}}}};
}

}  // namespace

Result<std::vector<std::uint8_t>> generateCrowdGlb(const CrowdOptions& options) {
    if (options.characters == 0 || options.characters > kMaxCrowdCharacters) {
        return makeError(ErrorCode::InvalidArgument, "The number of characters (" +
                                                         std::to_string(options.characters) +
                                                         ") must be between 1 and " +
                                                         std::to_string(kMaxCrowdCharacters) + ".");
    }
    json document = {{"asset", {{"version", "2.0"}, {"generator", "encore gen --crowd"}}},
                     {"scene", 0},
                     {"buffers", json::array()},
                     {"bufferViews", json::array()},
                     {"accessors", json::array()},
                     {"materials",
                      {{{"name", "character"},
                        {"pbrMetallicRoughness",
                         {{"baseColorFactor", {0.8, 0.45, 0.2, 1.0}},
                          {"metallicFactor", 0.0},
                          {"roughnessFactor", 0.6}}}}}},
                     {"nodes", json::array()},
                     {"skins", json::array()}};
    GlbBinaryChunk binary;
    document["meshes"] = {addCharacterMesh(document, binary)};

    // Shared by every character: the inverse bind matrices (bind pose at the origin) and each
    // joint's rotation keys (about Z, joint j swinging 0.12 (j + 1) radians).
    std::vector<float> inverseBinds;
    for (std::uint32_t j = 0; j < kCrowdJointsPerCharacter; ++j) {
        const glm::mat4 inverse =
            glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -kSegment * float(j), 0.0f));
        inverseBinds.insert(inverseBinds.end(), &inverse[0][0], &inverse[0][0] + 16);
    }
    const std::size_t inverseBindAccessor =
        binary.addAccessor(document, inverseBinds, kFloat, "MAT4", kCrowdJointsPerCharacter);
    constexpr std::uint32_t kKeys = 5;
    std::vector<std::size_t> rotationAccessors;
    for (std::uint32_t j = 0; j < kCrowdJointsPerCharacter; ++j) {
        const float swing = 0.12f * float(j + 1);
        std::vector<float> values;
        for (float angle : {0.0f, swing, 0.0f, -swing, 0.0f}) {
            const glm::quat q = glm::angleAxis(angle, glm::vec3(0.0f, 0.0f, 1.0f));
            values.insert(values.end(), {q.x, q.y, q.z, q.w});
        }
        rotationAccessors.push_back(binary.addAccessor(document, values, kFloat, "VEC4", kKeys));
    }
    std::vector<float> times;
    for (std::uint32_t key = 0; key < kKeys; ++key) {
        times.push_back(float(key) / float(kKeys - 1));
    }
    const std::size_t input =
        binary.addAccessor(document, times, kFloat, "SCALAR", kKeys, std::nullopt,
                           json{{times.front()}, {times.back()}});

    const auto side = static_cast<std::uint32_t>(std::ceil(std::sqrt(double(options.characters))));
    const float spacing = 1.0f;
    const float origin = -0.5f * float(side - 1) * spacing;
    json sceneNodes = json::array();
    json animations = json::array();
    for (std::uint32_t k = 0; k < options.characters; ++k) {
        const std::size_t root = document["nodes"].size();
        const float x = origin + float(k % side) * spacing;
        const float z = origin + float(k / side) * spacing;
        // The mesh node sits below the root too: skinning ignores its transform, but bounds,
        // framing and culling of the rest pose then find the character where it stands.
        document["nodes"].push_back(
            {{"name", "character " + std::to_string(k)},
             {"translation", {x, 0.0f, z}},
             {"children", {root + 1, root + 1 + kCrowdJointsPerCharacter}}});
        json skinJoints = json::array();
        for (std::uint32_t j = 0; j < kCrowdJointsPerCharacter; ++j) {
            json joint = {{"translation", {0.0f, j == 0 ? 0.0f : kSegment, 0.0f}}};
            if (j + 1 < kCrowdJointsPerCharacter) {
                joint["children"] = {root + 2 + j};
            }
            document["nodes"].push_back(joint);
            skinJoints.push_back(root + 1 + j);
        }
        document["nodes"].push_back({{"mesh", 0}, {"skin", k}});
        document["skins"].push_back(
            {{"joints", skinJoints}, {"inverseBindMatrices", inverseBindAccessor}});
        sceneNodes.push_back(root);

        // This character's animation: the shared keys (the same accessors for every character),
        // played out of step through Encore's time offset.
        json samplers = json::array();
        json channels = json::array();
        for (std::uint32_t j = 0; j < kCrowdJointsPerCharacter; ++j) {
            channels.push_back(
                {{"sampler", j}, {"target", {{"node", root + 1 + j}, {"path", "rotation"}}}});
            samplers.push_back(
                {{"input", input}, {"output", rotationAccessors[j]}, {"interpolation", "LINEAR"}});
        }
        animations.push_back(
            {{"name", "sway " + std::to_string(k)},
             {"samplers", samplers},
             {"channels", channels},
             {"extras", {{"encoreTimeOffset", std::fmod(0.37f * float(k), 1.0f)}}}});
    }
    document["animations"] = animations;
    document["buffers"].push_back({{"byteLength", binary.size()}});
    document["scenes"] = {{{"nodes", sceneNodes}}};

    return writeGlb(document, binary.take());
}

}  // namespace encore::scene
