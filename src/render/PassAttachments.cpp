#include "render/PassAttachments.h"

namespace encore::render {

PassAttachments passAttachments(const PassPlan& plan) {
    PassAttachments pass;
    const bool multiView = plan.viewCount > 1;
    const bool firstView = plan.view == 0;
    const bool lastView = plan.view + 1 >= plan.viewCount;

    // HDR: alpha is coverage, 0 where nothing is drawn, for the tone mapper's background.
    // Otherwise the background colour itself (linear: the sRGB target encodes the clear).
    const glm::vec3& background = plan.backgroundColor;
    pass.clearColor = plan.hdr ? wgpu::Color{0.0, 0.0, 0.0, 0.0}
                               : wgpu::Color{background.r, background.g, background.b, 1.0};

    // A single pass: clear, resolve a multisampled colour and discard it, discard depth.
    pass.colorLoadOp = wgpu::LoadOp::Clear;
    pass.colorStoreOp = plan.multisampled ? wgpu::StoreOp::Discard : wgpu::StoreOp::Store;
    pass.resolve = plan.multisampled;
    pass.depthLoadOp = wgpu::LoadOp::Clear;
    pass.depthStoreOp = wgpu::StoreOp::Discard;
    pass.depthClearValue = 1.0f;

    if (!firstView || plan.phase == DrawPhase::Second) {
        pass.colorLoadOp = wgpu::LoadOp::Load;  // Keep the views (or the phase) drawn before.
    }
    if (multiView) {
        pass.colorStoreOp = wgpu::StoreOp::Store;  // Multisampled contents survive the passes.
        if (!lastView) {
            // A resolve writes the whole target, whatever the viewport: resolve once, after the
            // last view, rather than the whole wide target once per view.
            pass.resolve = false;
        }
        // Depth likewise: cleared once for the whole target and kept between the passes, rather
        // than cleared whole by each (each view tests only its own strip).
        if (!firstView) {
            pass.depthLoadOp = wgpu::LoadOp::Load;
        }
        if (!lastView) {
            pass.depthStoreOp = wgpu::StoreOp::Store;
        }
    }
    if (plan.phase == DrawPhase::First) {
        pass.colorStoreOp = wgpu::StoreOp::Store;
        pass.resolve = false;  // The second pass resolves.
        pass.depthStoreOp = wgpu::StoreOp::Store;
    } else if (plan.phase == DrawPhase::Second) {
        pass.depthLoadOp = wgpu::LoadOp::Load;
    }

    if (plan.transmissionFollows) {
        // The transmission pass draws on: keep everything (the resolve above feeds the copy).
        pass.colorStoreOp = wgpu::StoreOp::Store;
        pass.depthStoreOp = wgpu::StoreOp::Store;
    }
    if (plan.transmission) {
        pass.colorLoadOp = wgpu::LoadOp::Load;
        pass.depthLoadOp = wgpu::LoadOp::Load;
        pass.colorStoreOp =
            plan.multisampled && lastView ? wgpu::StoreOp::Discard : wgpu::StoreOp::Store;
        pass.resolve = plan.multisampled && lastView;
        pass.depthStoreOp = lastView ? wgpu::StoreOp::Discard : wgpu::StoreOp::Store;
        pass.label = "encore transmission";
        pass.timestampLabel = "transmission";
        return pass;
    }

    switch (plan.phase) {
        case DrawPhase::Whole:
            pass.label = "encore frame";
            pass.timestampLabel = "scene";
            break;
        case DrawPhase::First:
            pass.label = "encore frame (first phase)";
            pass.timestampLabel = "scene (first phase)";
            break;
        case DrawPhase::Second:
            pass.label = "encore frame (second phase)";
            pass.timestampLabel = "scene (second phase)";
            break;
    }
    return pass;
}

}  // namespace encore::render
