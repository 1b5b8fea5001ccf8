#pragma once

// What a Renderer reports: each frame's timing and recorded calls (FrameResult), where a
// prepare's time went (PrepareTimes), what animation did (AnimationFrameStats) and the
// renderer's running counts (RendererStats, Renderer::stats).

#include <cstdint>
#include <optional>
#include <vector>

#include "encore/render/RendererOptions.h"
#include "encore/render/StrategyKind.h"
#include "encore/scene/AnimationPlayer.h"

namespace encore::render {

// WebGPU calls recorded for one frame (or into one bundle), tallied by RenderEncoder, plus what
// the draws drew. The case study's stats, separated: it summed vertex and index buffer sets.
struct DrawCounters {
    std::uint64_t setPipeline = 0;
    std::uint64_t setBindGroup = 0;
    std::uint64_t setVertexBuffer = 0;
    std::uint64_t setIndexBuffer = 0;
    std::uint64_t draw = 0;
    std::uint64_t drawIndexed = 0;
    std::uint64_t drawIndirect = 0;  // drawIndirect + drawIndexedIndirect.
    std::uint64_t executeBundles = 0;
    std::uint64_t primitives = 0;  // Primitive draws issued (one per draw call).
    std::uint64_t instances = 0;   // Sum of instanceCount over direct draws.
    std::uint64_t triangles = 0;   // Triangles of direct draws (list and strip topologies).

    std::uint64_t drawCalls() const { return draw + drawIndexed + drawIndirect; }
    // Every counted encoder call.
    std::uint64_t apiCalls() const {
        return setPipeline + setBindGroup + setVertexBuffer + setIndexBuffer + drawCalls() +
               executeBundles;
    }
    DrawCounters& operator+=(const DrawCounters& other);
    bool operator==(const DrawCounters&) const = default;
};

// One measured frame. CPU times are wall-clock on the calling thread; gpuMilliseconds comes
// from timestamp queries around the frame's passes when the device supports them.
struct FrameTiming {
    double encodeMilliseconds = 0.0;  // Recording: command encoder, passes, Finish.
    double submitMilliseconds = 0.0;  // Queue::Submit (Dawn records the Vulkan commands here).
    std::optional<double> gpuMilliseconds;

    double cpuMilliseconds() const { return encodeMilliseconds + submitMilliseconds; }
};

// Median and 95th percentile of a series.
struct Percentiles {
    double median = 0.0;
    double p95 = 0.0;

    static Percentiles of(std::vector<double> values);
};

// Where Renderer::prepare's time went, in milliseconds: the GPU scene's parts (geometry,
// instances, materials), then the strategy's (draws, for the materials-based strategies; other
// strategies' work counts only in `strategy`).
struct PrepareTimes {
    double release = 0.0;    // Freeing the previous scene (waiting for the GPU first, by default).
    double animation = 0.0;  // Lights and the animation player.
    double scene = 0.0;      // Building the GPU scene: the three parts below, animation buffers.
    double strategy = 0.0;   // Strategy::prepare, `draws` included.
    double geometry = 0.0;   // Vertex and index data, uploaded into the shared buffers.
    double instances = 0.0;  // Instance transforms and their bind group.
    double materials = 0.0;  // Textures (upload and mipmaps), samplers, material bind groups.
    // The textures' part of `materials` (MaterialResources::uploadTimes).
    double textureCreation = 0.0;
    double textureWrites = 0.0;
    double mipmaps = 0.0;
    double materialSubmit = 0.0;
    double draws = 0.0;   // Grouping the draws: pipelines (found or created), vertex bindings.
    double checks = 0.0;  // Collecting errors (out-of-memory scope, validation errors).

    double total() const { return release + animation + scene + strategy + checks; }
    PrepareTimes& operator+=(const PrepareTimes& other);
};

// The size of the GPU evaluation, fixed when it is created.
struct GpuAnimationStats {
    std::uint32_t animatedNodes = 0;  // Nodes some animation drives (pass 1 threads).
    std::uint32_t worldNodes = 0;     // Nodes at or below them (pass 2 threads).
    std::uint32_t levels = 0;         // Depth levels among those: pass 2 dispatches.
    std::uint32_t instances = 0;      // Instances whose transform they move.
    std::uint32_t joints = 0;         // Joint matrices of all skins.
    std::uint32_t dispatches = 0;     // Per frame.
    std::uint32_t copies = 0;         // Per frame (node-uniform strategies).
    std::uint64_t bytesPerFrame = 0;  // What the CPU writes per frame (clock times).
    // Clocks: one per distinct animation duration. Animations that share one (a crowd's
    // characters, each with its own extras.encoreTimeOffset) cost the CPU one float per frame.
    std::uint32_t clocks = 0;
    // Key times and values stored, each distinct run once however many samplers use it (with the
    // rest weights of animated nodes).
    std::uint64_t keyframeBytes = 0;
};

// What one AnimationBuffers::write() uploaded.
struct AnimationUploadStats {
    std::uint32_t jointsWritten = 0;
    std::uint32_t weightsWritten = 0;
    std::uint64_t bytesWritten = 0;
};

// A frame's timing (gpuMilliseconds only with a GPU timer set) and what it recorded.
// What one setAnimationTime() did: the player's work and what it uploaded.
struct AnimationFrameStats {
    AnimationEvaluation evaluation = AnimationEvaluation::Cpu;
    scene::AnimationStats player;  // CPU evaluation only.
    GpuAnimationStats gpu;         // GPU evaluation only: its size and per-frame dispatches.
    AnimationUploadStats upload;   // Joint matrices and morph weights.
    std::uint32_t instancesWritten = 0;
    // Instance transforms, joints and weights together (GPU: the animation times).
    std::uint64_t bytesWritten = 0;
};

// What the GPU drew in one frame, by rasteriser (Renderer::takeTriangleHistory).
struct DrawnTriangles {
    std::uint64_t hardware = 0;  // Through the graphics pipeline.
    std::uint64_t compute = 0;   // Rasterised in compute (the visibility strategy).
    std::uint64_t total() const { return hardware + compute; }
};

struct FrameResult : FrameTiming {
    DrawCounters counters;        // Calls recorded into the frame's render pass(es).
    DrawCounters bundleContents;  // What the executed bundles contain (recorded once).
    // What the frame's draws could draw: the triangles of its direct draws, of the bundles it
    // executed and of its indirect draws at full instance counts (submittedTriangles), summed
    // over views. Culling decides how many of them are drawn (Renderer::takeDrawnTriangles).
    std::uint64_t trianglesSubmitted = 0;
    // KHR_materials_transmission: copies of the scene made for transmissive surfaces (one per
    // frame that has any; 0 in scenes without them, which pay for nothing).
    std::uint32_t transmissionCopies = 0;
};

// A renderer's counts since it was created or since the last prepare(), for reports, the
// viewer's HUD and tests: what the command line's `stats`, benchmarks and `encore -v` print.
struct RendererStats {
    // The prepared strategy (Bundles and false before any prepare()).
    StrategyKind strategy = StrategyKind::Bundles;
    bool bundled = false;
    // Render pipelines the last prepare() or setStrategy() created (kept pipelines it found
    // instead are not counted).
    std::uint64_t pipelinesCreated = 0;
    // Render bundles the prepared strategy has recorded since it was prepared, re-recordings
    // included (0 for strategies that draw without bundles).
    std::uint64_t bundlesRecorded = 0;
    // GPU scenes built (prepare() and device recovery) and the geometry and texture bytes they
    // uploaded, edits included.
    std::uint64_t sceneUploads = 0;
    std::uint64_t uploadedBytes = 0;
    // Where the last prepare()'s time went.
    PrepareTimes prepare;
    // How long the environment maps took to build the last time they were built.
    double environmentBuildMilliseconds = 0.0;
};

}  // namespace encore::render
