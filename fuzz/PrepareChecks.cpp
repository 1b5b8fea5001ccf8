// The body of encore_fuzz_prepare and encore_fuzz_numbers (loadAndPrepare, FuzzCommon.h): load,
// then do everything CPU-side that src/render does with an accepted scene before it touches the
// GPU, checking the promises of SceneData.h on the way:
//  - every primitive's indices (readIndices) and vertex attributes (readFloats,
//    packedAccessorBytes, render::paddedVertexElements), their WebGPU vertex and index formats;
//  - every material's uniform (render::makeMaterialUniform) and texture slots, down to the
//    texture, image and sampler they name;
//  - instances, lights and cameras, and the automatic framing of the scene's bounds
//    (render::Camera::framing) and of each glTF camera (render::Camera::fromGltf);
//  - skins, morph targets and animations: every reference the player follows, then every
//    animation sampled alone at a few times (scene::AnimationPlayer), and all of them together.
// Inputs the loader rejects end here as in the load target.

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "FuzzCommon.h"
#include "RenderBridge.h"
#include "encore/render/Camera.h"
#include "encore/scene/AnimationPlayer.h"

namespace encore::fuzz {
namespace {

using namespace encore::scene;

// Folds values into a sum that is returned, so that no read is optimised away.
struct Sink {
    double sum = 0.0;
    void add(float value) { sum += std::isfinite(value) ? value : 1.0; }
    void add(const glm::vec4& value) { add(value.x + value.y + value.z + value.w); }
    void add(const glm::mat4& value) {
        for (int column = 0; column < 4; ++column) {
            add(value[column]);
        }
    }
};

void checkAccessor(const SceneData& scene, AccessorId id) {
    ENCORE_FUZZ_CHECK(id.valid() && id.index() < scene.accessors.size());
    const Accessor& accessor = scene.accessors[id.index()];
    ENCORE_FUZZ_CHECK(accessor.view.valid() && accessor.view.index() < scene.bufferViews.size());
    const BufferView& view = scene.bufferViews[accessor.view.index()];
    ENCORE_FUZZ_CHECK(view.buffer.valid() && view.buffer.index() < scene.buffers.size());
    ENCORE_FUZZ_CHECK(accessor.byteStride != 0);
    ENCORE_FUZZ_CHECK(accessor.componentCount >= 1 && accessor.componentCount <= 4);
    const std::uint64_t bufferSize = scene.buffers[view.buffer.index()].bytes.size();
    ENCORE_FUZZ_CHECK(view.byteOffset <= bufferSize &&
                      view.byteLength <= bufferSize - view.byteOffset);
    if (accessor.count > 0) {
        const std::uint64_t span =
            std::uint64_t(accessor.count - 1) * accessor.byteStride + accessor.elementSize();
        ENCORE_FUZZ_CHECK(accessor.byteOffset <= view.byteLength &&
                          span <= view.byteLength - accessor.byteOffset);
    }
}

void prepareGeometry(const SceneData& scene, Sink& sink) {
    for (const Mesh& mesh : scene.meshes) {
        for (const Primitive& primitive : mesh.primitives) {
            ENCORE_FUZZ_CHECK(primitive.material.valid() &&
                              primitive.material.index() < scene.materials.size());
            ENCORE_FUZZ_CHECK(primitive.attribute(Semantic::Position).has_value());
            ENCORE_FUZZ_CHECK(primitive.attribute(Semantic::Normal).has_value());
            for (const VertexAttribute& attribute : primitive.attributes) {
                checkAccessor(scene, attribute.accessor);
                const Accessor& accessor = scene.accessors[attribute.accessor.index()];
                ENCORE_FUZZ_CHECK(accessor.count >= primitive.vertexCount);
                // Joints and weights are not drawn; every other attribute must be bindable.
                if (bindsAttribute(attribute.semantic)) {
                    ENCORE_FUZZ_CHECK(hasVertexFormat(accessor));
                }
                const auto floats = scene.readFloats(attribute.accessor);
                ENCORE_FUZZ_CHECK(floats.size() == accessor.count);
                for (const glm::vec4& value : floats) {
                    sink.add(value);
                }
                const auto packed = scene.packedAccessorBytes(attribute.accessor);
                ENCORE_FUZZ_CHECK(packed.size() ==
                                  std::size_t(accessor.count) * accessor.elementSize());
                std::uint32_t stride = 0;
                const std::size_t padded = paddedVertexBytes(scene, attribute.accessor, stride);
                ENCORE_FUZZ_CHECK(stride % 4 == 0 && stride >= accessor.elementSize());
                ENCORE_FUZZ_CHECK(padded == std::size_t(accessor.count) * stride);
            }
            if (primitive.indices) {
                checkAccessor(scene, *primitive.indices);
                const Accessor& accessor = scene.accessors[primitive.indices->index()];
                ENCORE_FUZZ_CHECK(accessor.componentType == ComponentType::Uint16 ||
                                  accessor.componentType == ComponentType::Uint32);
                ENCORE_FUZZ_CHECK(accessor.componentCount == 1);
                ENCORE_FUZZ_CHECK(accessor.byteStride == accessor.elementSize());
                ENCORE_FUZZ_CHECK(hasIndexFormat(accessor));
                for (const std::uint32_t index : scene.readIndices(*primitive.indices)) {
                    ENCORE_FUZZ_CHECK(index < primitive.vertexCount);
                }
            }
            sink.add(glm::vec4(primitive.bounds.center(), primitive.bounds.radius()));
        }
    }
}

void prepareMaterials(const SceneData& scene, Sink& sink) {
    for (const Sampler& sampler : scene.samplers) {
        sink.add(float(samplerChecksum(sampler)));
    }
    for (const Material& material : scene.materials) {
        sink.add(materialUniformChecksum(material));
        for (std::uint32_t slot = 0; slot < materialSlotCount(); ++slot) {
            const auto reference = materialSlotTexture(material, slot);
            if (!reference) {
                continue;
            }
            ENCORE_FUZZ_CHECK(reference->texture.valid() &&
                              reference->texture.index() < scene.textures.size());
            const Texture& texture = scene.textures[reference->texture.index()];
            ENCORE_FUZZ_CHECK(texture.sampler.valid() &&
                              texture.sampler.index() < scene.samplers.size());
            if (texture.image.valid()) {
                ENCORE_FUZZ_CHECK(texture.image.index() < scene.images.size());
                const Image& image = scene.images[texture.image.index()];
                ENCORE_FUZZ_CHECK(image.rgba8.empty() ||
                                  image.rgba8.size() ==
                                      std::size_t(image.width) * image.height * 4);
            }
        }
    }
}

void prepareSceneGraph(const SceneData& scene, Sink& sink) {
    for (const Instance& instance : scene.instances) {
        ENCORE_FUZZ_CHECK(instance.mesh.valid() && instance.mesh.index() < scene.meshes.size());
        sink.add(instance.world);
        sink.add(instance.normalMatrix);
    }
    for (const LightInstance& light : scene.lightInstances) {
        ENCORE_FUZZ_CHECK(light.light.valid() && light.light.index() < scene.lights.size());
        sink.add(glm::vec4(light.position, 1.0f));
    }
    for (const CameraInstance& placed : scene.cameraInstances) {
        ENCORE_FUZZ_CHECK(placed.camera.valid() && placed.camera.index() < scene.cameras.size());
        for (const float aspect : {1.5f, 0.0f}) {
            const auto camera = render::Camera::fromGltf(scene.cameras[placed.camera.index()],
                                                         placed.world, aspect);
            sink.add(camera.viewProjection());
        }
    }
    for (const float yaw : {0.0f, 1.0f}) {
        const auto camera = render::Camera::framing(scene.bounds, 16.0f / 9.0f, yaw);
        sink.add(camera.viewProjection());
    }
}

void checkMorphTarget(const SceneData& scene, const Primitive& primitive, AccessorId id) {
    checkAccessor(scene, id);
    const Accessor& accessor = scene.accessors[id.index()];
    ENCORE_FUZZ_CHECK(accessor.componentType == ComponentType::Float32);
    ENCORE_FUZZ_CHECK(accessor.componentCount == 3);
    ENCORE_FUZZ_CHECK(accessor.count == primitive.vertexCount);
}

void prepareAnimation(const SceneData& scene, Sink& sink) {
    for (const Mesh& mesh : scene.meshes) {
        for (const Primitive& primitive : mesh.primitives) {
            ENCORE_FUZZ_CHECK(primitive.targets.size() == mesh.weights.size());
            for (const MorphTarget& target : primitive.targets) {
                for (const auto& slot : {target.position, target.normal, target.tangent}) {
                    if (slot) {
                        checkMorphTarget(scene, primitive, *slot);
                    }
                }
            }
        }
    }
    for (const Node& node : scene.nodes) {
        if (node.skin) {
            ENCORE_FUZZ_CHECK(node.skin->index() < scene.skins.size() && node.mesh);
        }
        ENCORE_FUZZ_CHECK(node.weights.size() ==
                          (node.mesh ? scene.meshes[node.mesh->index()].weights.size() : 0));
    }
    for (const Skin& skin : scene.skins) {
        ENCORE_FUZZ_CHECK(!skin.joints.empty());
        ENCORE_FUZZ_CHECK(skin.inverseBindMatrices.size() == skin.joints.size());
        for (const NodeId joint : skin.joints) {
            ENCORE_FUZZ_CHECK(joint.index() < scene.nodes.size());
        }
    }
    for (const Animation& animation : scene.animations) {
        for (const AnimationSampler& sampler : animation.samplers) {
            ENCORE_FUZZ_CHECK(!sampler.times.empty());
            const std::size_t perKey = sampler.interpolation == Interpolation::CubicSpline ? 3 : 1;
            ENCORE_FUZZ_CHECK(sampler.values.size() ==
                              sampler.times.size() * perKey * sampler.components);
        }
        for (const AnimationChannel& channel : animation.channels) {
            ENCORE_FUZZ_CHECK(channel.sampler < animation.samplers.size());
            ENCORE_FUZZ_CHECK(channel.node.index() < scene.nodes.size());
            const std::uint32_t components = animation.samplers[channel.sampler].components;
            const Node& node = scene.nodes[channel.node.index()];
            ENCORE_FUZZ_CHECK(components == (channel.path == AnimationPath::Weights
                                                 ? node.weights.size()
                                             : channel.path == AnimationPath::Rotation ? 4u
                                                                                       : 3u));
        }
    }
    AnimationPlayer player(scene);
    auto collect = [&] {
        for (const glm::mat4& world : player.instanceWorlds()) {
            sink.add(world);
        }
        for (const glm::mat4& joint : player.jointMatrices()) {
            sink.add(joint);
        }
        for (const float weight : player.morphWeights()) {
            sink.add(weight);
        }
        ENCORE_FUZZ_CHECK(player.changedInstances().size() <= scene.instances.size());
    };
    for (std::size_t a = 0; a < scene.animations.size(); ++a) {
        ENCORE_FUZZ_CHECK(player.select(AnimationId(a)).ok());
        const Animation& animation = scene.animations[a];
        for (const double t :
             {double(animation.start), 0.5 * (double(animation.start) + animation.end),
              double(animation.end) + 1.0}) {
            player.evaluate(t);
            collect();
        }
    }
    player.selectAll();
    player.setMode(PlaybackMode::Loop);
    player.evaluate(1.25);
    collect();
}

}  // namespace

void loadAndPrepare(const std::uint8_t* data, std::size_t size) {
    const auto scene = loadFuzzInput(data, size);
    if (!scene) {
        return;
    }
    Sink sink;
    prepareGeometry(*scene, sink);
    prepareMaterials(*scene, sink);
    prepareSceneGraph(*scene, sink);
    prepareAnimation(*scene, sink);
    volatile double keep = sink.sum;
    (void)keep;
}

}  // namespace encore::fuzz
