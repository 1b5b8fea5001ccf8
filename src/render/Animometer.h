#pragma once

// The Animometer scene: the classic render-bundle benchmark of the WebGPU samples and Dawn (a
// port of MotionMark's Animometer). It draws N small spinning triangles, each with its own
// setBindGroup(1, ...) and draw(3), on one pipeline and one vertex buffer, so a frame is almost
// nothing but per-draw API calls: it measures the cost of encoding draws directly against
// replaying them from a render bundle.
//
// Each triangle's parameters (scale, centre, spin speed and phase, drawn from a seeded random
// generator) live in a 256-byte slot of one uniform buffer written once at creation. A frame
// writes only the time uniform (group 0); the vertex shader (animometer.wgsl) spins each
// triangle around its centre from that time and colours it from its position on screen.
//
// Per frame, direct mode records setPipeline, setBindGroup(0), setVertexBuffer and then N pairs
// of setBindGroup(1) + draw, so lastFrameCounters() shows 1 setPipeline, N + 1 setBindGroup and
// N draws. Bundle mode records exactly those calls once, at creation, into a render bundle
// (bundleContents()) and each frame records a single executeBundles. The target is cleared to
// opaque black (kClearColor) every frame.
//
// Driver limit seen on Mesa 25.0 lavapipe: beyond about 65,000 triangles it crashes inside
// libvulkan_lvp (allocating descriptor pools, for the per-triangle bind groups at creation and
// for the dynamic-offset binds of one pass), so CPU-only runs should stay at or below 50,000.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <string>
#include <vector>

#include "encore/core/Result.h"
#include "encore/gpu/Context.h"
#include "encore/image/ImageCodec.h"
#include "encore/render/RenderTarget.h"
#include "encore/render/RendererStats.h"
#include "gpu/GpuTimer.h"
#include "render/RenderEncoder.h"
#include "shaders/ShaderLibrary.h"

namespace encore::render {

struct AnimometerOptions {
    std::uint32_t triangles = 20000;  // 1 .. kMaxAnimometerTriangles.
    // Record all draws once into a render bundle at creation and replay it every frame.
    bool bundle = false;
    // How each draw selects its triangle's slot of the parameter buffer:
    //   false: N bind groups, one per slot (the sample's default);
    //   true:  one bind group with a dynamic offset, setBindGroup(1, group, slot * 256).
    bool dynamicOffsets = false;
    std::uint32_t width = 512;
    std::uint32_t height = 512;
    std::uint32_t seed = 1;  // Same seed, same triangles, whatever the mode.
};

inline constexpr std::uint32_t kMaxAnimometerTriangles = 1000000;

class AnimometerScene {
  public:
    static constexpr wgpu::Color kClearColor{0.0, 0.0, 0.0, 1.0};

    // Creates the target, pipeline, buffers and bind groups (and, in bundle mode, records the
    // bundle). Fails with InvalidArgument when the triangle count is 0 or above
    // kMaxAnimometerTriangles or the size is not a valid target size, with LimitExceeded when
    // the parameter buffer (256 bytes per triangle) exceeds the device's maxBufferSize, and on
    // any WebGPU error raised while creating. The context must outlive the scene.
    static Result<AnimometerScene> create(gpu::Context& context,
                                          shaders::ShaderLibrary& shaders,
                                          const AnimometerOptions& options);

    // Writes the time uniform, records the frame's pass (the draws directly, or executeBundles
    // of the bundle recorded at creation) and submits it. encodeMilliseconds covers creating the
    // command encoder through Finish, submitMilliseconds covers Queue::Submit, as in Renderer.
    // With a timer, the pass is timed and gpuMilliseconds waits for its result after submit.
    FrameTiming renderFrame(float timeSeconds, gpu::GpuTimer* timer = nullptr);

    // Gives the target a new size; the pipeline and the bundle (recorded for formats and sample
    // count, not size) stay.
    Result<void> resize(std::uint32_t width, std::uint32_t height);
    const RenderTarget& target() const { return mTarget; }

    // Calls recorded into the last frame's pass (in bundle mode: executeBundles 1, nothing else).
    const DrawCounters& lastFrameCounters() const { return mFrameCounters; }
    // Calls recorded into the bundle (all zero in direct mode).
    const DrawCounters& bundleContents() const { return mBundleContents; }

    // Waits for submitted work, reads the target back, and fails if WebGPU reported an error.
    Result<image::ImageRgba8> readImage();

    const AnimometerOptions& options() const { return mOptions; }
    // e.g. "animometer 20000 triangles, bind groups, bundle".
    std::string describe() const;

  private:
    AnimometerScene() = default;
    // The one recording function for both the pass and the bundle.
    void recordDraws(RenderEncoder& encoder) const;

    gpu::Context* mContext = nullptr;
    AnimometerOptions mOptions;
    RenderTarget mTarget;
    wgpu::RenderPipeline mPipeline;
    wgpu::Buffer mVertices;
    wgpu::Buffer mTime;
    wgpu::Buffer mTriangles;
    wgpu::BindGroup mTimeGroup;
    // One per triangle, or a single dynamic-offset group in dynamicOffsets mode.
    std::vector<wgpu::BindGroup> mTriangleGroups;
    wgpu::RenderBundle mBundle;  // Null in direct mode.
    DrawCounters mBundleContents;
    DrawCounters mFrameCounters;
};

}  // namespace encore::render
