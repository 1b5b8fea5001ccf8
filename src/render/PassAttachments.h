#pragma once

// How each render pass of a frame treats the target's colour and depth: load or clear, store or
// discard, resolve or not, and with which clear values. Decided from the frame's shape alone,
// without any GPU object, so that tests check it without a device; Renderer copies the answer
// into the attachments RenderTarget gives it.
//
// A frame is one of three shapes:
//  - One view, one pass (DrawPhase::Whole). Colour and depth are cleared; a multisampled colour
//    is resolved into the scene texture and itself discarded; depth is discarded.
//  - Several views side by side, one pass per view, each drawing its own vertical strip. The
//    first pass clears colour and depth for the whole target and every pass but the last keeps
//    them for the next (views after the first load them). A resolve writes the whole target
//    whatever the viewport, so only the last pass resolves, and only it discards depth.
//  - One view in two passes (DrawPhase::First, then DrawPhase::Second: two-phase occlusion
//    culling). The first clears, keeps its colour unresolved and keeps its depth; the second
//    loads both, resolves and discards as a single pass would.
//
// KHR_materials_transmission adds a pass per view after those (TransmissionPass.h): the passes
// before it keep colour and depth for it (transmissionFollows), it loads both, and it resolves
// and discards as the pass it follows would have (its own plan, `transmission`).
//
// The clear colour: with an HDR target, transparent black (alpha is coverage, 0 where nothing is
// drawn, which the tone mapper composites over the background); otherwise the opaque background
// colour, linear (the sRGB target encodes it).

#include <webgpu/webgpu_cpp.h>

#include <cstddef>
#include <glm/vec3.hpp>

#include "render/Strategy.h"

namespace encore::render {

// One pass of a frame, as PassAttachments.h describes the shapes.
struct PassPlan {
    std::size_t view = 0;                // The view this pass draws, counted from the left.
    std::size_t viewCount = 1;           // Views side by side in the frame.
    DrawPhase phase = DrawPhase::Whole;  // First or Second only when viewCount is 1.
    bool multisampled = false;           // The target draws multisampled and resolves.
    bool hdr = false;                    // The target keeps linear HDR colour with coverage.
    glm::vec3 backgroundColor{0.0f};     // Linear; the clear colour without HDR.
    bool transmissionFollows = false;    // A transmission pass draws into this one's result.
    bool transmission = false;           // This is the transmission pass of `view`.
};

// What a pass does with the target's attachments. Plain values: the caller fills the wgpu
// structs, dropping the resolve target where `resolve` is false.
struct PassAttachments {
    wgpu::LoadOp colorLoadOp = wgpu::LoadOp::Clear;
    wgpu::StoreOp colorStoreOp = wgpu::StoreOp::Store;
    bool resolve = false;  // Resolves the multisampled colour into the scene texture.
    wgpu::Color clearColor{0.0, 0.0, 0.0, 0.0};
    wgpu::LoadOp depthLoadOp = wgpu::LoadOp::Clear;
    wgpu::StoreOp depthStoreOp = wgpu::StoreOp::Discard;
    float depthClearValue = 1.0f;     // The far plane.
    const char* label = "";           // The render pass's label.
    const char* timestampLabel = "";  // The pass's name in GPU timings.
};

PassAttachments passAttachments(const PassPlan& plan);

}  // namespace encore::render
