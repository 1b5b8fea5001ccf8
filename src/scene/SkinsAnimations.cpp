// Skins and animations: parsed from the JSON, then checked against the loaded nodes, meshes and
// accessors and decoded into SceneData (inverse bind matrices as mat4, sampler keys and values as
// floats), so that the player never meets a value it has to check.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>

#include "scene/LoadContext.h"

namespace encore::scene {
namespace {

std::string countText(std::uint64_t count, std::string_view what) {
    return std::to_string(count) + " " + std::string(what) + (count == 1 ? "" : "s");
}

// The accessor's components as floats (normalised integers mapped), in element order;
// matrices read column by column, skipping glTF's column padding of 1- and 2-byte types.
std::vector<float> readComponents(const SceneData& scene,
                                  const GltfAccessor& source,
                                  AccessorId id) {
    const Accessor& accessor = scene.accessors[id.index()];
    const auto bytes = scene.accessorBytes(id);
    std::vector<float> result;
    if (bytes.empty()) {
        return result;
    }
    const std::uint32_t size = componentSize(accessor.componentType);
    const std::uint32_t components = source.componentCount;
    const std::uint32_t rows = source.isMatrix ? (components == 4   ? 2
                                                  : components == 9 ? 3
                                                                    : 4)
                                               : components;
    const std::uint32_t columnBytes = source.isMatrix ? (rows * size + 3) / 4 * 4 : rows * size;
    result.resize(std::size_t(accessor.count) * components);
    for (std::size_t i = 0; i < accessor.count; ++i) {
        const std::uint8_t* element = bytes.data() + i * accessor.byteStride;
        for (std::uint32_t c = 0; c < components; ++c) {
            const std::uint8_t* at = element + (c / rows) * columnBytes + (c % rows) * size;
            float value = 0.0f;
            switch (accessor.componentType) {
                case ComponentType::Float32:
                    std::memcpy(&value, at, 4);
                    break;
                case ComponentType::Int8: {
                    const auto v = static_cast<std::int8_t>(*at);
                    value = accessor.normalized ? std::max(v / 127.0f, -1.0f) : float(v);
                    break;
                }
                case ComponentType::Uint8:
                    value = accessor.normalized ? *at / 255.0f : float(*at);
                    break;
                case ComponentType::Int16: {
                    std::int16_t v;
                    std::memcpy(&v, at, 2);
                    value = accessor.normalized ? std::max(v / 32767.0f, -1.0f) : float(v);
                    break;
                }
                case ComponentType::Uint16: {
                    std::uint16_t v;
                    std::memcpy(&v, at, 2);
                    value = accessor.normalized ? v / 65535.0f : float(v);
                    break;
                }
                case ComponentType::Uint32: {
                    std::uint32_t v;
                    std::memcpy(&v, at, 4);
                    value = float(v);
                    break;
                }
            }
            result[i * components + c] = value;
        }
    }
    return result;
}

std::optional<Interpolation> interpolationFromName(std::string_view name) {
    if (name == "LINEAR") {
        return Interpolation::Linear;
    }
    if (name == "STEP") {
        return Interpolation::Step;
    }
    if (name == "CUBICSPLINE") {
        return Interpolation::CubicSpline;
    }
    return std::nullopt;
}

std::optional<AnimationPath> pathFromName(std::string_view name) {
    if (name == "translation") {
        return AnimationPath::Translation;
    }
    if (name == "rotation") {
        return AnimationPath::Rotation;
    }
    if (name == "scale") {
        return AnimationPath::Scale;
    }
    if (name == "weights") {
        return AnimationPath::Weights;
    }
    return std::nullopt;
}

// Decodes one sampler: input times checked (scalar float, finite, strictly increasing), output
// read as floats and its count checked against the keys.
Result<AnimationSampler> convertSampler(const LoadContext& context,
                                        const GltfAnimationSampler& source,
                                        const std::string& name) {
    const GltfDocument& document = context.document;
    const SceneData& scene = context.scene;
    AnimationSampler sampler;
    const auto interpolation = interpolationFromName(source.interpolation);
    if (!interpolation) {
        return makeError(ErrorCode::InvalidFormat, name + " has an unknown interpolation ('" +
                                                       source.interpolation +
                                                       "'; expected LINEAR, STEP or CUBICSPLINE).");
    }
    sampler.interpolation = *interpolation;
    const GltfAccessor& input = document.accessors[source.input];
    if (input.type != "SCALAR" || input.componentType != ComponentType::Float32 ||
        input.normalized) {
        return makeError(ErrorCode::InvalidFormat,
                         name + " has an input (accessor " + std::to_string(source.input) + ", " +
                             input.type + ") that is not a SCALAR of floats; key times must be.");
    }
    sampler.times = readComponents(scene, input, AccessorId(source.input));
    for (std::size_t k = 0; k < sampler.times.size(); ++k) {
        const float time = sampler.times[k];
        if (!std::isfinite(time)) {
            return makeError(ErrorCode::InvalidFormat,
                             name + " has a key time that is not finite (key " + std::to_string(k) +
                                 " of accessor " + std::to_string(source.input) + ").");
        }
        if (k > 0 && !(time > sampler.times[k - 1])) {
            return makeError(ErrorCode::InvalidFormat,
                             name + " has key times that are not strictly increasing (key " +
                                 std::to_string(k) + " at " + formatNumber(time) + " s follows " +
                                 formatNumber(sampler.times[k - 1]) + " s in accessor " +
                                 std::to_string(source.input) + ").");
        }
    }
    const GltfAccessor& output = document.accessors[source.output];
    if (output.isMatrix) {
        return makeError(ErrorCode::InvalidFormat, name + " has an output (accessor " +
                                                       std::to_string(source.output) +
                                                       ") of matrices (" + output.type + ").");
    }
    const std::uint64_t perKey = sampler.interpolation == Interpolation::CubicSpline ? 3 : 1;
    const std::uint64_t keys = sampler.times.size();
    const std::uint64_t outputCount = output.count;
    // Weights outputs are scalars, one per morph target and key: a multiple of the key count.
    if (outputCount % (keys * perKey) != 0 || outputCount == 0) {
        return makeError(
            ErrorCode::InvalidFormat,
            name + " has " + countText(outputCount, "output value") + " (accessor " +
                std::to_string(source.output) + ") for " + countText(keys, "key time") +
                (perKey == 3 ? " (CUBICSPLINE needs 3 values per key: in-tangent, value, "
                               "out-tangent, for each morph target with weights)"
                             : " (it needs one per key, for each morph target with weights)") +
                ".");
    }
    sampler.values = readComponents(scene, output, AccessorId(source.output));
    sampler.components =
        static_cast<std::uint32_t>(outputCount / (keys * perKey)) * output.componentCount;
    return sampler;
}

// Checks that the channel's sampler output fits its path: element type and width.
Result<void> checkChannelOutput(const LoadContext& context,
                                const GltfAnimationSampler& source,
                                const AnimationSampler& sampler,
                                AnimationPath path,
                                std::uint32_t targets,
                                const std::string& name) {
    const GltfAccessor& output = context.document.accessors[source.output];
    const std::string accessor =
        "output (accessor " + std::to_string(source.output) + ", " + output.type + ")";
    const bool isFloat = output.componentType == ComponentType::Float32 && !output.normalized;
    const bool isNormalized = output.normalized && output.componentType != ComponentType::Uint32 &&
                              output.componentType != ComponentType::Float32;
    switch (path) {
        case AnimationPath::Translation:
        case AnimationPath::Scale:
            if (output.type != "VEC3" || !isFloat) {
                return makeError(ErrorCode::InvalidFormat,
                                 name + " animates " + std::string(animationPathName(path)) +
                                     " with an " + accessor + " that is not a VEC3 of floats.");
            }
            break;
        case AnimationPath::Rotation:
            if (output.type != "VEC4" || !(isFloat || isNormalized)) {
                return makeError(ErrorCode::InvalidFormat,
                                 name + " animates rotation with an " + accessor +
                                     " that is not a VEC4 of floats or of normalised integers.");
            }
            break;
        case AnimationPath::Weights: {
            if (output.type != "SCALAR" || !(isFloat || isNormalized)) {
                return makeError(ErrorCode::InvalidFormat,
                                 name + " animates weights with an " + accessor +
                                     " that is not a SCALAR of floats or of normalised integers.");
            }
            break;
        }
    }
    const std::uint32_t expected = path == AnimationPath::Weights    ? targets
                                   : path == AnimationPath::Rotation ? 4
                                                                     : 3;
    if (sampler.components != expected) {
        const bool cubic = sampler.interpolation == Interpolation::CubicSpline;
        const std::uint64_t perElement = path == AnimationPath::Weights ? targets : 1;
        return makeError(
            ErrorCode::InvalidFormat,
            name + " animates " + std::string(animationPathName(path)) +
                (path == AnimationPath::Weights ? " of " + countText(targets, "morph target")
                                                : std::string()) +
                " but its sampler's " + accessor + " has " + countText(output.count, "element") +
                " for " + countText(sampler.times.size(), "key time") + " (needs " +
                std::to_string(sampler.times.size() * (cubic ? 3 : 1) * perElement) +
                (cubic ? ": CUBICSPLINE stores in-tangent, value and out-tangent per key" : "") +
                ").");
    }
    return {};
}

}  // namespace

std::string_view animationPathName(AnimationPath path) {
    switch (path) {
        case AnimationPath::Translation:
            return "translation";
        case AnimationPath::Rotation:
            return "rotation";
        case AnimationPath::Scale:
            return "scale";
        case AnimationPath::Weights:
            return "weights";
    }
    return "unknown";
}

std::string_view interpolationName(Interpolation mode) {
    switch (mode) {
        case Interpolation::Step:
            return "STEP";
        case Interpolation::Linear:
            return "LINEAR";
        case Interpolation::CubicSpline:
            return "CUBICSPLINE";
    }
    return "UNKNOWN";
}

Result<void> parseAnimations(const Json& root, GltfDocument& document) {
    return forEachElement(root, "animations", "animation", [&](FieldReader& reader, std::size_t) {
        GltfAnimation animation;
        animation.name = reader.string("name");
        // extras may hold anything; only Encore's own key is read, and it must be a number.
        if (const Json* extras = reader.objectIfAny("extras")) {
            FieldReader fields(*extras, reader.element() + " extras");
            animation.timeOffset = fields.number("encoreTimeOffset", 0.0);
            // Beyond this a float time loses whole keyframe intervals (and 1e39 is no float).
            constexpr double kMaxTimeOffset = 1e6;
            if (!fields.failed() && std::abs(animation.timeOffset) > kMaxTimeOffset) {
                fields.fail(ErrorCode::InvalidFormat,
                            fields.element() + ": encoreTimeOffset " +
                                formatNumber(animation.timeOffset) +
                                " is out of range (at most 1000000 seconds either way).");
            }
            if (fields.failed()) {
                reader.fail(fields.error().code, fields.error().message);
            }
        }
        const Json* channels = reader.array("channels");
        const Json* samplers = reader.array("samplers");
        for (std::size_t c = 0; channels && c < channels->size() && !reader.failed(); ++c) {
            FieldReader fields((*channels)[c], reader.element() + ", channel " + std::to_string(c));
            GltfAnimationChannel channel;
            channel.sampler = fields.requiredIndex("sampler");
            if (const Json* target = fields.object("target")) {
                FieldReader targetFields(*target, fields.element() + " target");
                channel.node = targetFields.optionalIndex("node");
                channel.path = targetFields.requiredString("path");
                if (targetFields.failed()) {
                    fields.fail(targetFields.error().code, targetFields.error().message);
                }
            } else if (!fields.failed()) {
                fields.fail(ErrorCode::InvalidFormat, fields.element() + " has no 'target'.");
            }
            if (fields.failed()) {
                reader.fail(fields.error().code, fields.error().message);
            }
            animation.channels.push_back(std::move(channel));
        }
        for (std::size_t s = 0; samplers && s < samplers->size() && !reader.failed(); ++s) {
            FieldReader fields((*samplers)[s], reader.element() + ", sampler " + std::to_string(s));
            GltfAnimationSampler sampler;
            sampler.input = fields.requiredIndex("input");
            sampler.output = fields.requiredIndex("output");
            sampler.interpolation = fields.string("interpolation", "LINEAR");
            if (fields.failed()) {
                reader.fail(fields.error().code, fields.error().message);
            }
            animation.samplers.push_back(std::move(sampler));
        }
        document.animations.push_back(std::move(animation));
    });
}

Result<void> convertSkins(LoadContext& context) {
    const GltfDocument& document = context.document;
    SceneData& scene = context.scene;
    scene.skins.reserve(document.skins.size());
    for (std::size_t s = 0; s < document.skins.size(); ++s) {
        const GltfSkin& source = document.skins[s];
        const std::string name = "skin " + std::to_string(s);
        if (source.joints.empty()) {
            return makeError(ErrorCode::InvalidFormat, name + " has no joints.");
        }
        Skin skin;
        skin.name = source.name;
        for (std::uint32_t joint : source.joints) {
            skin.joints.push_back(NodeId(joint));
        }
        if (source.skeleton) {
            skin.skeleton = NodeId(*source.skeleton);
        }
        skin.inverseBindMatrices.assign(skin.joints.size(), glm::mat4(1.0f));
        if (source.inverseBindMatrices) {
            const std::uint32_t index = *source.inverseBindMatrices;
            const GltfAccessor& accessor = document.accessors[index];
            if (accessor.type != "MAT4" || accessor.componentType != ComponentType::Float32) {
                return makeError(ErrorCode::InvalidFormat,
                                 name + " has inverseBindMatrices (accessor " +
                                     std::to_string(index) + ", " + accessor.type +
                                     ") that are not MAT4 floats.");
            }
            if (accessor.count < skin.joints.size()) {
                return makeError(
                    ErrorCode::InvalidFormat,
                    name + " has " + countText(skin.joints.size(), "joint") + " but " +
                        std::to_string(accessor.count) +
                        (accessor.count == 1 ? " inverse bind matrix" : " inverse bind matrices") +
                        " (accessor " + std::to_string(index) + ").");
            }
            const auto values = readComponents(scene, accessor, AccessorId(index));
            for (std::size_t j = 0; j < skin.joints.size(); ++j) {
                std::memcpy(&skin.inverseBindMatrices[j][0][0], values.data() + j * 16,
                            16 * sizeof(float));
            }
        }
        scene.skins.push_back(std::move(skin));
    }
    // A skinned primitive's joint indices must name joints of the node's skin: the renderer
    // indexes one array holding the joint matrices of all skins.
    std::unordered_map<std::uint32_t, std::uint32_t> largestJoint;  // By accessor.
    for (std::size_t n = 0; n < scene.nodes.size(); ++n) {
        const Node& node = scene.nodes[n];
        if (!node.skin || !node.mesh) {
            continue;
        }
        const std::size_t joints = scene.skins[node.skin->index()].joints.size();
        const Mesh& mesh = scene.meshes[node.mesh->index()];
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            for (const Semantic semantic : {Semantic::Joints0, Semantic::Joints1}) {
                const auto accessor = mesh.primitives[p].attribute(semantic);
                if (!accessor) {
                    continue;
                }
                const auto key = static_cast<std::uint32_t>(accessor->index());
                auto found = largestJoint.find(key);
                if (found == largestJoint.end()) {
                    float largest = 0.0f;
                    for (const glm::vec4& value : scene.readFloats(*accessor)) {
                        largest = std::max({largest, value.x, value.y, value.z, value.w});
                    }
                    found = largestJoint.emplace(key, static_cast<std::uint32_t>(largest)).first;
                }
                if (found->second >= joints) {
                    return makeError(ErrorCode::InvalidFormat,
                                     "mesh " + std::to_string(node.mesh->index()) + ", primitive " +
                                         std::to_string(p) + " has joint index " +
                                         std::to_string(found->second) + " in " +
                                         std::string(semanticName(semantic)) + ", but node " +
                                         std::to_string(n) + " skins it with skin " +
                                         std::to_string(node.skin->index()) + ", which has " +
                                         countText(joints, "joint") + ".");
                }
            }
        }
    }
    return {};
}

Result<void> convertAnimations(LoadContext& context) {
    const GltfDocument& document = context.document;
    SceneData& scene = context.scene;
    scene.animations.reserve(document.animations.size());
    for (std::size_t a = 0; a < document.animations.size(); ++a) {
        const GltfAnimation& source = document.animations[a];
        const std::string name = "animation " + std::to_string(a);
        Animation animation;
        animation.name = source.name;
        animation.timeOffset = static_cast<float>(source.timeOffset);
        for (std::size_t s = 0; s < source.samplers.size(); ++s) {
            AnimationSampler sampler;
            ENCORE_TRY_ASSIGN(sampler, convertSampler(context, source.samplers[s],
                                                      name + ", sampler " + std::to_string(s)));
            animation.samplers.push_back(std::move(sampler));
        }
        bool any = false;
        for (std::size_t c = 0; c < source.channels.size(); ++c) {
            const GltfAnimationChannel& channel = source.channels[c];
            const std::string where = name + ", channel " + std::to_string(c);
            if (channel.sampler >= source.samplers.size()) {
                return makeError(ErrorCode::InvalidFormat,
                                 where + " refers to sampler " + std::to_string(channel.sampler) +
                                     ", but the animation has " +
                                     countText(source.samplers.size(), "sampler") + ".");
            }
            if (!channel.node) {
                continue;  // Targeted by an extension (KHR_animation_pointer): not played.
            }
            const auto path = pathFromName(channel.path);
            if (!path) {
                ENCORE_TRY(context.warn(ErrorCode::Unsupported,
                                        where + " animates an unknown path ('" + channel.path +
                                            "'); the channel is ignored."));
                continue;
            }
            const Node& node = scene.nodes[*channel.node];
            std::uint32_t targets = 0;
            if (*path == AnimationPath::Weights) {
                targets = node.mesh ? static_cast<std::uint32_t>(
                                          scene.meshes[node.mesh->index()].weights.size())
                                    : 0;
                if (targets == 0) {
                    // glTF forbids it, but nothing drawn depends on it: a warning (an error
                    // with --strict), and the channel is dropped.
                    ENCORE_TRY(context.warn(
                        ErrorCode::InvalidFormat,
                        where + " animates the weights of node " + std::to_string(*channel.node) +
                            ", which has no mesh with morph targets; the channel is ignored."));
                    continue;
                }
            } else if (node.hasMatrix) {
                ENCORE_TRY(context.warn(
                    ErrorCode::InvalidFormat,
                    where + " animates node " + std::to_string(*channel.node) +
                        ", which has a matrix (glTF allows only TRS on animated nodes); the "
                        "matrix is decomposed into TRS."));
            }
            const AnimationSampler& sampler = animation.samplers[channel.sampler];
            ENCORE_TRY(checkChannelOutput(context, source.samplers[channel.sampler], sampler, *path,
                                          targets, where));
            animation.channels.push_back(
                AnimationChannel{channel.sampler, NodeId(*channel.node), *path});
            animation.start =
                any ? std::min(animation.start, sampler.times.front()) : sampler.times.front();
            animation.end =
                any ? std::max(animation.end, sampler.times.back()) : sampler.times.back();
            any = true;
        }
        scene.animations.push_back(std::move(animation));
    }
    return {};
}

}  // namespace encore::scene
