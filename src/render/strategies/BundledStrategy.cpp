#include "BundledStrategy.h"

namespace encore::render {

BundledStrategy::BundledStrategy(std::unique_ptr<Strategy> recorded)
    : mRecorded(std::move(recorded)) {}

Result<void> BundledStrategy::prepare(const RenderSetup& setup, const scene::SceneData& scene) {
    mSetup = &setup;
    mStale = true;
    return mRecorded->prepare(setup, scene);
}

void BundledStrategy::beforePass(const wgpu::CommandEncoder& commands, const FrameState& frame) {
    mRecorded->beforePass(commands, frame);
    if (mStale) {
        // The wrapped strategies read nothing of the frame while recording (the camera comes
        // from the frame uniforms), so one recording serves every later frame.
        mBundle = recordBundle(*mSetup, "encore " + std::string(strategyName(kind())) + " frame",
                               [&](RenderEncoder& encoder) { mRecorded->encode(encoder, frame); });
        ++mRecordings;
        mStale = false;
    }
}

void BundledStrategy::encode(RenderEncoder& encoder, const FrameState&) const {
    encoder.executeBundles(std::span(&mBundle.bundle, 1));
}

Result<void> BundledStrategy::updateInstance(std::size_t instance, const glm::mat4& world) {
    return mRecorded->updateInstance(instance, world);
}

InstanceTransformTargets BundledStrategy::instanceTransformTargets() const {
    return mRecorded->instanceTransformTargets();
}

Result<void> BundledStrategy::updateMaterial(scene::MaterialId material,
                                             const scene::Material& value) {
    return mRecorded->updateMaterial(material, value);
}

Result<void> BundledStrategy::replaceBaseColorImage(scene::MaterialId material,
                                                    const scene::Image& image) {
    ENCORE_TRY(mRecorded->replaceBaseColorImage(material, image));
    mStale = true;  // The bundle binds the old texture's bind group.
    return {};
}

}  // namespace encore::render
