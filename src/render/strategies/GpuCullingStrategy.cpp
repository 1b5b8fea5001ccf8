#include "render/strategies/GpuCullingStrategy.h"

#include <cassert>
#include <chrono>
#include <map>

#include "core/Elapsed.h"

namespace encore::render {

namespace {

// The last frame's triangle counts of `culler` (none before it has culled).
std::optional<GpuTriangleCounts> gpuTriangleCountsOf(const GpuCuller& culler) {
    if (!culler.indirectArguments()) {
        return std::nullopt;
    }
    return GpuTriangleCounts{culler.indirectArguments(), culler.drawnTrianglesOffset(),
                             std::nullopt, submittedTriangles(culler.draws())};
}

}  // namespace

Result<void> GpuCullingStrategy::prepare(const RenderSetup& setup, const GpuScene& scene) {
    mSetup = &setup;
    mBundles = BundledFrame();
    mFirstPhaseBundle = BundledFrame();
    mTransmission = BundledFrame();
    mCulled.clear();
    mCullerCreated = false;
    ENCORE_TRY(mDraws.prepare(setup, scene));
    const auto start = std::chrono::steady_clock::now();
    auto grouped = groupDraws();
    setup.prepareTimes.draws += millisecondsSince(start);
    return grouped;
}

Result<void> GpuCullingStrategy::refresh() {
    if (!mDraws.stale()) {
        return {};
    }
    ENCORE_TRY(mDraws.regroup());
    return groupDraws();
}

InstanceTransformTargets GpuCullingStrategy::instanceTransformTargets() const {
    return mDraws.scene().instances().transformTargets();
}

Result<void> GpuCullingStrategy::groupDraws() {
    const scene::SceneData& scene = mDraws.scene().data();
    const InstanceBuffer& instances = mDraws.scene().instances();
    const RenderSetup& setup = *mSetup;
    // A regrouping (a material gained textures, another material variant) keeps the culler and
    // its draws, whose spheres may have moved since: each primitive keeps its draw index. Only
    // when the opaque draws themselves changed (a variant that blends, or binds other vertex
    // inputs) is the culler made again.
    DrawIndices drawOf;
    for (const CulledPipeline& pipeline : mCulled) {
        for (const CulledMaterial& material : pipeline.materials) {
            for (const CulledPrimitive& primitive : material.primitives) {
                drawOf[{primitive.bindings, primitive.firstInstance}] = primitive.draw;
            }
        }
    }
    if (mCullerCreated && !sameDraws(drawOf)) {
        mCullerCreated = false;
    }
    mCulled.clear();

    // Same grouping as `materials`; each draw becomes an indirect draw of the culled variant.
    std::vector<CulledDraw> draws;
    for (const MaterialDrawGroups::PipelineGroup& group : mDraws.opaque()) {
        PipelineKey key = group.key;
        key.shader.instanceSource = shaders::InstanceSource::VisibleList;
        ENCORE_TRY_ASSIGN(auto pipeline, mDraws.pipelines().get(key));
        CulledPipeline culled{pipeline, key.shader, {}};
        for (const MaterialDrawGroups::MaterialGroup& material : group.materials) {
            CulledMaterial culledMaterial{material.material, {}};
            for (const PrimitiveDraw& primitive : material.primitives) {
                std::size_t draw = draws.size();
                if (mCullerCreated) {
                    const auto existing =
                        drawOf.find({primitive.bindings, primitive.instances.first});
                    assert(existing != drawOf.end());
                    draw = existing->second;
                } else {
                    draws.push_back(culledDraw(primitive));
                }
                culledMaterial.primitives.push_back({primitive.bindings, primitive.instances.first,
                                                     draw, primitive.sceneInstance,
                                                     primitive.primitive});
            }
            culled.materials.push_back(std::move(culledMaterial));
        }
        mCulled.push_back(std::move(culled));
    }
    if (mCullerCreated) {
        return {};
    }

    std::vector<std::size_t> instanceAt(instances.size());
    for (std::uint32_t slot = 0; slot < instances.size(); ++slot) {
        instanceAt[slot] = instances.instanceAt(slot);
    }
    const AnimationBuffers* animation = mDraws.scene().animation();
    CullingBounds bounds = CullingBounds::build(scene, instanceAt, animation);
    ENCORE_TRY_ASSIGN(mCuller, GpuCuller::create(setup, instances, animation, std::move(bounds),
                                                 std::move(draws)));
    mCullerCreated = true;
    return {};
}

bool GpuCullingStrategy::sameDraws(const DrawIndices& drawOf) const {
    std::size_t count = 0;
    for (const MaterialDrawGroups::PipelineGroup& group : mDraws.opaque()) {
        for (const MaterialDrawGroups::MaterialGroup& material : group.materials) {
            for (const PrimitiveDraw& primitive : material.primitives) {
                if (!drawOf.contains({primitive.bindings, primitive.instances.first})) {
                    return false;
                }
                ++count;
            }
        }
    }
    return count == drawOf.size();
}

CulledDraw GpuCullingStrategy::culledDraw(const PrimitiveDraw& primitive) const {
    const PrimitiveBindings& bindings = *primitive.bindings;
    CulledDraw draw;
    draw.instances = primitive.instances;
    draw.indexed = bindings.indices.has_value();
    draw.elementCount = bindings.indices ? bindings.indices->count : bindings.vertexCount;
    draw.topology = bindings.topology;
    // The coarser levels live in the index view after level 0 (scene::LevelOfDetail), which the
    // index binding reaches: each is a range of the same index buffer.
    const scene::SceneData& scene = mDraws.scene().data();
    const scene::Mesh& mesh = scene.meshes[scene.instances[primitive.sceneInstance].mesh.value];
    const scene::Primitive& source = mesh.primitives[primitive.primitive];
    if (bindings.indices && source.indices) {
        const scene::Accessor& levelZero = scene.accessors[source.indices->value];
        for (const scene::LevelOfDetail& level : source.levels) {
            const scene::Accessor& indices = scene.accessors[level.indices.value];
            draw.coarserLevels.push_back(
                {static_cast<std::uint32_t>((indices.byteOffset - levelZero.byteOffset) /
                                            levelZero.elementSize()),
                 indices.count, level.error});
        }
    }
    return draw;
}

StrategyReport GpuCullingStrategy::report() const {
    StrategyReport report;
    report.bundleContents = mFirstPhaseBundle.contents();
    report.bundleContents += mBundles.contents();
    report.bundleContents += mTransmission.contents();
    report.bundlesRecorded =
        mFirstPhaseBundle.recorded() + mBundles.recorded() + mTransmission.recorded();
    report.culler = &mCuller;
    report.gpuTriangleCounts = gpuTriangleCountsOf(mCuller);
    return report;
}

bool GpuCullingStrategy::drawsInTwoPhases(const FrameState& frame) const {
    // A frozen culling camera sees another view than the depth drawn: frustum culling only.
    return frame.culling.occlusion && !frame.cullingCamera;
}

void GpuCullingStrategy::beforePass(const wgpu::CommandEncoder& commands, const FrameState& frame) {
    CullingView view;
    view.camera = frame.cullingCamera.value_or(frame.camera);
    if (!frame.cullingCamera) {
        view.views = frame.views;
    }
    view.targetWidth = frame.targetWidth;
    view.targetHeight = frame.targetHeight;
    view.options = frame.culling;
    view.twoPhases = frame.phase == DrawPhase::First;
    mCuller.encodeFirstPhase(mSetup->queue, commands, view, frame.timer);
    if (mUseBundles) {
        // Phase 1's draws, then phase 2's and the blended geometry: a frame of one pass replays
        // both (phase 2's counts stay zero), a two-phase frame one per pass.
        mFirstPhaseBundle.update(
            *mSetup, mDraws.scene().generation(), {},
            [this](RenderEncoder& encoder) { encodeCulled(encoder, 0); },
            [](RenderEncoder&, std::span<const std::uint32_t>) {});
        mBundles.update(
            *mSetup, mDraws.scene().generation(), mDraws.blendOrder(frame.camera.position),
            [this](RenderEncoder& encoder) { encodeCulled(encoder, 1); },
            [this](RenderEncoder& encoder, std::span<const std::uint32_t> order) {
                mDraws.setSharedBindGroups(encoder);
                mDraws.encodeBlended(encoder, order);
            });
        if (drawsTransmission()) {
            mDraws.updateTransmissionBundle(mTransmission, *mSetup);
        }
    }
}

void GpuCullingStrategy::encodeTransmission(RenderEncoder& encoder, const FrameState&) const {
    if (mUseBundles) {
        mTransmission.execute(encoder);
        return;
    }
    mDraws.setSharedBindGroups(encoder);
    mDraws.encodeTransmissive(encoder);
}

void GpuCullingStrategy::betweenPhases(const wgpu::CommandEncoder& commands,
                                       const FrameState& frame,
                                       const wgpu::Texture& depth) {
    mCuller.encodeSecondPhase(commands, depth, frame.timer);
}

void GpuCullingStrategy::encodeCulled(RenderEncoder& encoder, std::uint32_t phase) const {
    encoder.setBindGroup(0, mSetup->frame->bindGroup());
    for (const CulledPipeline& group : mCulled) {
        encoder.setPipeline(group.pipeline);
        for (const CulledMaterial& material : group.materials) {
            mDraws.bindMaterial(encoder, material.material);
            for (const CulledPrimitive& primitive : material.primitives) {
                if (group.shader.animated()) {
                    mDraws.scene().animation()->bind(encoder, group.shader, primitive.sceneInstance,
                                                     primitive.primitive);
                }
                bindGeometry(encoder, *primitive.bindings);
                const std::uint32_t levels = mCuller.draws()[primitive.draw].levelCount();
                for (std::uint32_t level = 0; level < levels; ++level) {
                    encoder.setBindGroup(1, mCuller.drawBindGroup(),
                                         mCuller.dynamicOffset(primitive.draw, level, phase));
                    const std::uint64_t offset =
                        mCuller.argumentsOffset(primitive.draw, level, phase);
                    if (primitive.bindings->indices) {
                        encoder.drawIndexedIndirect(mCuller.indirectArguments(), offset);
                    } else {
                        encoder.drawIndirect(mCuller.indirectArguments(), offset);
                    }
                }
            }
        }
    }
}

void GpuCullingStrategy::encode(RenderEncoder& encoder, const FrameState& frame) const {
    if (mUseBundles) {
        if (frame.phase != DrawPhase::Second) {
            mFirstPhaseBundle.execute(encoder);
        }
        if (frame.phase != DrawPhase::First) {
            mBundles.execute(encoder);
        }
        return;
    }
    // A frame of one pass draws phase 1's records only: phase 2's counts stay zero.
    encodeCulled(encoder, frame.phase == DrawPhase::Second ? 1 : 0);
    if (frame.phase != DrawPhase::First && !mDraws.blended().empty()) {
        mDraws.setSharedBindGroups(encoder);  // Blended pipelines use the plain instance layout.
        mDraws.encodeBlended(encoder, mDraws.blendOrder(frame.camera.position));
    }
}

}  // namespace encore::render
