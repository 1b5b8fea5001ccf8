#pragma once

// The passes of a frame that some strategies draw beyond encode()'s one scene pass, asked for
// through Strategy::framePasses(): a second phase after culling against the first's depth, a
// transmission pass, a scene pass straight into the resolved texture, or the whole frame
// composed in compute. Every answer defaults to "no": a strategy overrides what it draws.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>

#include "encore/core/Result.h"
#include "render/RenderEncoder.h"
#include "render/Strategy.h"

namespace encore::render {

// Where a strategy that composes the frame in compute (FramePasses::composesFrame) writes it.
struct FrameComposition {
    // What a pixel nothing covers holds: the scene pass's clear colour (linear).
    wgpu::Color background{0.0, 0.0, 0.0, 0.0};
    const wgpu::PassTimestampWrites* timestampWrites = nullptr;  // For the composing pass.
};

class FramePasses {
  public:
    // Whether this frame (of one view) is drawn in two passes: beforePass, encode() with
    // DrawPhase::First, betweenPhases() with the first pass's depth, encode() with
    // DrawPhase::Second. Asked before beforePass; false: one pass, DrawPhase::Whole.
    virtual bool drawsInTwoPhases(const FrameState& frame) const {
        (void)frame;
        return false;
    }
    // Between the two passes of a two-phase frame: GPU work that reads the first pass's depth.
    virtual void betweenPhases(const wgpu::CommandEncoder& commands,
                               const FrameState& frame,
                               const wgpu::Texture& depth) {
        (void)commands;
        (void)frame;
        (void)depth;
    }

    // KHR_materials_transmission: whether encode() leaves out surfaces with transmission, for
    // encodeTransmission() to draw in a pass of their own once the Renderer has copied the scene
    // drawn so far (render/TransmissionPass.h). False (the default) when the scene has none, and
    // in strategies that shade no materials (which draw every surface alike).
    virtual bool drawsTransmission() const { return false; }
    // Records the transmissive surfaces into the transmission pass of `frame`'s view (called
    // only when drawsTransmission()); as encode(), it sets every piece of state it uses.
    virtual void encodeTransmission(RenderEncoder& encoder, const FrameState& frame) const {
        (void)encoder;
        (void)frame;
    }

    // Whether, on a multisampled target, the scene passes need nothing but what encode() draws
    // from the strategy's own per-sample data, already averaged per pixel: then the renderer
    // draws them at one sample straight into the target's resolved texture, without depth
    // (FrameState::resolvedPass), and skips the multisampled target, its clears and its resolve
    // (on the H100's few graphics units those cost about four times a one-sample pass).
    virtual bool composesResolved() const { return false; }

    // Whether the strategy writes every pixel of the frame itself in compute (composeFrame),
    // so that the renderer records no scene render pass at all. Asked only for frames the
    // renderer could compose so: one phase, no transmission pass, no pass images, and a plain
    // background colour (an environment is drawn by a render pass).
    virtual bool composesFrame(const FrameState& frame) const {
        (void)frame;
        return false;
    }
    // Records the frame's composition after beforePass(): every pixel of `frame.composedView`
    // (the target's one-sample scene colour) written, uncovered ones with `target.background`.
    virtual void composeFrame(const wgpu::CommandEncoder& commands,
                              const FrameState& frame,
                              const FrameComposition& target) {
        (void)commands;
        (void)frame;
        (void)target;
    }

    // Whether the strategy can draw into a target of `width` x `height` (after prepare()):
    // strategies whose passes use buffers that grow with the target (visibility) say here, with
    // an error naming the device limit, when they would exceed it. The Renderer asks on prepare
    // and resize.
    virtual Result<void> checkTarget(std::uint32_t width, std::uint32_t height) const {
        (void)width;
        (void)height;
        return {};
    }

  protected:
    ~FramePasses() = default;  // Owned as the Strategy that implements it.
};

}  // namespace encore::render
