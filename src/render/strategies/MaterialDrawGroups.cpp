#include "render/strategies/MaterialDrawGroups.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <unordered_map>

#include "core/Elapsed.h"

namespace encore::render {

namespace {

// The variant a primitive and its material need: vertex inputs that exist and are read
// (TEXCOORD_0, COLOR_0; TANGENT only under a normal map; TEXCOORD_1 only when a texture reads
// it), MASK's discard, whether the material binds textures at all, samples them through more
// than one sampler, and uses the costly extensions (iridescence, anisotropy, transmission,
// diffuse transmission).
// Everything else (which slots have textures, clearcoat, sheen, unlit) is uniform data and
// 1-pixel default textures, so it shares the variant.
shaders::ShaderVariantKey materialVariant(const scene::Primitive& primitive,
                                          const scene::Material& material,
                                          const MaterialResources& resources,
                                          scene::MaterialId materialId) {
    shaders::ShaderVariantKey key;
    key.materialTextures = resources.textured(materialId);
    key.samplerPalette = key.materialTextures && resources.samplesThroughPalette(materialId);
    key.materialExtensions = materialShadesExtensions(material);
    key.instanceSource = shaders::InstanceSource::InstanceStorage;
    key.materials = true;
    key.hasTexcoord = primitive.attribute(scene::Semantic::Texcoord0).has_value();
    key.hasColor = primitive.attribute(scene::Semantic::Color0).has_value();
    key.alphaMask = material.alphaMode == scene::AlphaMode::Mask;
    key.hasTangent = materialUsesTangents(material) && !material.unlit &&
                     primitive.attribute(scene::Semantic::Tangent).has_value();
    key.hasTexcoord1 = materialUsesTexcoord1(material) &&
                       primitive.attribute(scene::Semantic::Texcoord1).has_value();
    return key;
}

// The attributes a shader variant reads, in the order GeometryBuffers binds them.
std::vector<scene::Semantic> variantSemantics(const shaders::ShaderVariantKey& key) {
    std::vector<scene::Semantic> semantics = {scene::Semantic::Position, scene::Semantic::Normal};
    appendAnimationSemantics(key, semantics);
    if (key.hasTexcoord) {
        semantics.push_back(scene::Semantic::Texcoord0);
    }
    if (key.hasColor) {
        semantics.push_back(scene::Semantic::Color0);
    }
    if (key.hasTangent) {
        semantics.push_back(scene::Semantic::Tangent);
    }
    if (key.hasTexcoord1) {
        semantics.push_back(scene::Semantic::Texcoord1);
    }
    return semantics;
}

// The semantics as a set of bits, to tell the bindings of one primitive apart.
std::uint32_t semanticBits(std::span<const scene::Semantic> semantics) {
    std::uint32_t bits = 0;
    for (const scene::Semantic semantic : semantics) {
        bits |= 1u << std::uint32_t(semantic);
    }
    return bits;
}

}  // namespace

Result<const PrimitiveBindings*> MaterialDrawGroups::bindingsFor(
    std::size_t mesh,
    std::size_t index,
    std::span<const scene::Semantic> semantics) {
    const std::uint32_t bits = semanticBits(semantics);
    PrimitiveBinding& first = mPrimitiveBindings[mesh][index];
    if (first.bindings && first.semantics == bits) {
        return first.bindings;
    }
    // Another set of inputs for a primitive bound before (a material variant with a normal map
    // reads TANGENT): rare, so kept apart from the first set.
    const auto other = mOtherBindings.find({mesh, index, bits});
    if (other != mOtherBindings.end()) {
        return other->second;
    }
    const scene::Primitive& primitive = mScene->data().meshes[mesh].primitives[index];
    ENCORE_TRY_ASSIGN(auto bindings, mScene->geometry().bind(primitive, semantics));
    mBindings.push_back(std::make_unique<PrimitiveBindings>(std::move(bindings)));
    const PrimitiveBindings* bound = mBindings.back().get();
    if (!first.bindings) {
        first = {bits, bound};
    } else {
        mOtherBindings.emplace(std::tuple{mesh, index, bits}, bound);
    }
    return bound;
}

Result<void> MaterialDrawGroups::prepare(const RenderSetup& setup,
                                         const GpuScene& scene,
                                         PrimitiveFilter filter) {
    mSetup = &setup;
    mFilter = std::move(filter);
    mScene = &scene;
    mFrameGroup = setup.frame->bindGroup();
    mPipelines = strategyPipelineCache(setup, mOwnPipelines);
    mBindings.clear();
    mOtherBindings.clear();
    const scene::SceneData& data = scene.data();
    mPrimitiveBindings.assign(data.meshes.size(), {});
    for (std::size_t mesh = 0; mesh < data.meshes.size(); ++mesh) {
        mPrimitiveBindings[mesh].assign(data.meshes[mesh].primitives.size(), {});
    }
    const auto start = std::chrono::steady_clock::now();
    auto grouped = regroup();
    setup.prepareTimes.draws += millisecondsSince(start);
    return grouped;
}

Result<void> MaterialDrawGroups::refresh() {
    return stale() ? regroup() : Result<void>{};
}

Result<void> MaterialDrawGroups::regroup() {
    const scene::SceneData& scene = mScene->data();
    const InstanceBuffer& instances = mScene->instances();
    const MaterialResources& materials = mScene->materials();
    const AnimationBuffers* animation = mScene->animation();
    const RenderSetup& setup = *mSetup;
    mGeneration = mScene->generation();
    mOpaque.clear();
    mBlended.clear();
    mTransmissive.clear();

    // Opaque (and transmissive) groups in first-use order: pipeline -> material -> primitives.
    struct GroupIndex {
        std::unordered_map<PipelineKey, std::size_t, PipelineKeyHash> groupOfKey;
        std::map<std::pair<std::size_t, scene::MaterialId>, std::size_t> materialGroupOf;
    };
    GroupIndex opaqueIndex;
    GroupIndex transmissiveIndex;
    for (std::size_t mesh = 0; mesh < scene.meshes.size(); ++mesh) {
        if (instances.meshRange(scene::MeshId(mesh)).count == 0) {
            continue;
        }
        const auto& primitives = scene.meshes[mesh].primitives;
        for (std::size_t index = 0; index < primitives.size(); ++index) {
            if (mFilter && !mFilter(scene::MeshId(mesh), index)) {
                continue;
            }
            const scene::Primitive& primitive = primitives[index];
            // The material of the selected KHR_materials_variants variant, if any.
            const scene::MaterialId materialId = mScene->materialOf(scene::MeshId(mesh), index);
            const scene::Material& material = scene.materials[materialId.index()];
            shaders::ShaderVariantKey variant =
                materialVariant(primitive, material, materials, materialId);
            if (animation) {
                animation->addVariantFlags(scene::MeshId(mesh), index, variant);
            }
            // A regrouping keeps the bindings of inputs bound before.
            ENCORE_TRY_ASSIGN(const PrimitiveBindings* bound,
                              bindingsFor(mesh, index, variantSemantics(variant)));

            PipelineKey key = meshPipelineKey(setup, *bound, variant);
            key.cullMode = material.doubleSided ? wgpu::CullMode::None : wgpu::CullMode::Back;
            key.blend = material.alphaMode == scene::AlphaMode::Blend;
            // Mirrored instances flip the winding, so they need the other front face.
            for (bool mirrored : {false, true}) {
                const InstanceRange range = instances.meshRange(scene::MeshId(mesh), mirrored);
                if (range.count == 0) {
                    continue;
                }
                key.frontFace = mirrored ? wgpu::FrontFace::CW : wgpu::FrontFace::CCW;
                ENCORE_TRY_ASSIGN(auto pipeline, mPipelines->get(key));
                // KHR_materials_transmission: drawn in the transmission pass, after the copy of
                // everything else (blended ones too, unsorted: they write no depth there).
                const bool transmissive = material.transmission.has_value();
                if (key.blend && !transmissive) {
                    for (std::uint32_t slot = range.first; slot < range.first + range.count;
                         ++slot) {
                        // Where the instance is now: edits before a regrouping count.
                        const glm::mat4& world =
                            mScene->instanceWorlds()[instances.instanceAt(slot)];
                        const glm::vec3 center = primitive.bounds.empty()
                                                     ? glm::vec3(world[3])
                                                     : primitive.bounds.transformed(world).center();
                        mBlended.push_back(
                            {pipeline, materialId, bound, slot, center, variant, index});
                    }
                    continue;
                }
                std::vector<PipelineGroup>& groups = transmissive ? mTransmissive : mOpaque;
                GroupIndex& groupIndex = transmissive ? transmissiveIndex : opaqueIndex;
                auto [group, inserted] = groupIndex.groupOfKey.try_emplace(key, groups.size());
                if (inserted) {
                    groups.push_back({key, pipeline, {}});
                }
                auto [materialGroup, newMaterial] = groupIndex.materialGroupOf.try_emplace(
                    {group->second, materialId}, groups[group->second].materials.size());
                if (newMaterial) {
                    groups[group->second].materials.push_back({materialId, {}});
                }
                groups[group->second].materials[materialGroup->second].primitives.push_back(
                    {bound, range, instances.instanceAt(range.first), index});
            }
        }
    }
    return {};
}

void MaterialDrawGroups::setSharedBindGroups(RenderEncoder& encoder) const {
    encoder.setBindGroup(0, mFrameGroup);
    encoder.setBindGroup(1, mScene->instances().bindGroup());
}

void MaterialDrawGroups::encodeOpaque(RenderEncoder& encoder) const {
    encodeGroups(encoder, mOpaque);
}

void MaterialDrawGroups::encodeTransmissive(RenderEncoder& encoder) const {
    encodeGroups(encoder, mTransmissive);
}

void MaterialDrawGroups::encodeGroups(RenderEncoder& encoder,
                                      std::span<const PipelineGroup> groups) const {
    for (const PipelineGroup& group : groups) {
        encoder.setPipeline(group.pipeline);
        for (const MaterialGroup& material : group.materials) {
            bindMaterial(encoder, material.material);
            for (const PrimitiveDraw& primitive : material.primitives) {
                if (group.key.shader.animated()) {
                    mScene->animation()->bind(encoder, group.key.shader, primitive.sceneInstance,
                                              primitive.primitive);
                }
                bindGeometry(encoder, *primitive.bindings);
                drawGeometry(encoder, *primitive.bindings, primitive.instances.count,
                             primitive.instances.first);
            }
        }
    }
}

std::vector<std::uint32_t> MaterialDrawGroups::blendOrder(const glm::vec3& cameraPosition) const {
    std::vector<std::pair<float, std::uint32_t>> keyed;
    keyed.reserve(mBlended.size());
    for (std::uint32_t i = 0; i < mBlended.size(); ++i) {
        const glm::vec3 offset = mBlended[i].center - cameraPosition;
        keyed.emplace_back(glm::dot(offset, offset), i);
    }
    // Farthest first; ties keep scene order so the result is deterministic.
    std::stable_sort(keyed.begin(), keyed.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    std::vector<std::uint32_t> order;
    order.reserve(keyed.size());
    for (const auto& [distance, index] : keyed) {
        order.push_back(index);
    }
    return order;
}

void MaterialDrawGroups::encodeBlended(RenderEncoder& encoder,
                                       std::span<const std::uint32_t> order) const {
    WGPURenderPipeline currentPipeline = nullptr;
    scene::MaterialId currentMaterial;
    const PrimitiveBindings* currentBindings = nullptr;
    for (std::uint32_t index : order) {
        const BlendedDraw& draw = mBlended[index];
        if (currentPipeline != draw.pipeline.Get()) {
            encoder.setPipeline(draw.pipeline);
            currentPipeline = draw.pipeline.Get();
        }
        if (currentMaterial != draw.material) {
            bindMaterial(encoder, draw.material);
            currentMaterial = draw.material;
        }
        if (currentBindings != draw.bindings) {
            bindGeometry(encoder, *draw.bindings);
            currentBindings = draw.bindings;
        }
        if (draw.shader.animated()) {
            mScene->animation()->bind(encoder, draw.shader,
                                      mScene->instances().instanceAt(draw.instanceSlot),
                                      draw.primitive);
        }
        drawGeometry(encoder, *draw.bindings, 1, draw.instanceSlot);
    }
}

void MaterialDrawGroups::bindMaterial(RenderEncoder& encoder, scene::MaterialId material) const {
    encoder.setBindGroup(2, mScene->materials().drawBindGroup(material));
}

void MaterialDrawGroups::updateTransmissionBundle(BundledFrame& bundle,
                                                  const RenderSetup& setup) const {
    bundle.update(
        setup, scene().generation(), {},
        [this](RenderEncoder& encoder) {
            setSharedBindGroups(encoder);
            encodeTransmissive(encoder);
        },
        [](RenderEncoder&, std::span<const std::uint32_t>) {});
}

}  // namespace encore::render
