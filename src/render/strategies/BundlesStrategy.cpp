#include "BundlesStrategy.h"

namespace encore::render {

Result<void> BundlesStrategy::prepare(const RenderSetup& setup, const scene::SceneData& scene) {
    ENCORE_TRY(MaterialsStrategy::prepare(setup, scene));
    mBundles = BundledFrame();
    return {};
}

void BundlesStrategy::beforePass(const wgpu::CommandEncoder&, const FrameState& frame) {
    mBundles.update(
        *mSetup, mMaterials->generation(), blendOrder(frame.camera.position),
        [this](RenderEncoder& encoder) {
            setSharedBindGroups(encoder);
            encodeOpaque(encoder);
        },
        [this](RenderEncoder& encoder, std::span<const std::uint32_t> order) {
            setSharedBindGroups(encoder);
            encodeBlended(encoder, order);
        });
}

void BundlesStrategy::encode(RenderEncoder& encoder, const FrameState&) const {
    mBundles.execute(encoder);
}

}  // namespace encore::render
