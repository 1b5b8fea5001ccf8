#pragma once

// Which strategy draws each model of a batch. An explicit BatchOptions::strategy draws them all.
// With BatchOptions::chooseStrategyPerModel (`--strategy auto`, the default), a model that
// draws many triangles goes to the visibility strategy, the others to bundles
// (gpu-culling-bundles with levels of detail): on the H200, whose graphics pipeline runs on few
// units, a dense model of 1.59 M triangles per view took 22.5 ms of GPU with bundles and 4.5 with
// visibility (3.4x the views per second), while the smallest shared models lost more on the CPU
// (clusters at load, longer recording) than they gained on the GPU (docs/batch.md, Strategies).

#include <cstdint>
#include <limits>
#include <span>

#include "encore/batch/Batch.h"
#include "encore/render/StrategyKind.h"

namespace encore::gpu {
class Context;
}

namespace encore::batch {

struct BatchStrategy {
    static constexpr std::uint64_t kNever = std::numeric_limits<std::uint64_t>::max();

    render::StrategyChoice base;  // The explicit strategy, or auto's for light models.
    // Models drawing at least this many triangles (SceneData::drawnTriangleCount) are drawn with
    // the visibility strategy instead of `base`; kNever: none is.
    std::uint64_t visibilityFromTriangles = kNever;
    // And models of any size that draw only opaque, static triangles
    // (SceneData::drawsOnlyOpaqueStaticTriangles): auto's rule at four samples on a GPU.
    bool visibilityForOpaqueStatic = false;

    render::StrategyChoice forModel(std::uint64_t drawnTriangles, bool opaqueStatic) const;
    bool mayChooseVisibility() const { return visibilityFromTriangles != kNever; }
    // Whether models are loaded with clusters (scene::LoadOptions::buildClusters), from how
    // many triangles (clustersFromTriangles) and whether for opaque, static ones of any size:
    // exactly those the visibility strategy draws.
    bool buildsClusters() const;
    std::uint64_t clustersFromTriangles() const;
};

// BatchOptions::strategy, or with chooseStrategyPerModel (the default) auto's choice for the
// batch's devices: visibility from BatchOptions::visibilityFromTriangles
// (autoVisibilityTriangles(samples) unless set; at four samples also the models that draw only
// opaque, static triangles, unless it is set) where every device has the visibility feature,
// is not a CPU (lavapipe rasterises in compute 4.5x slower than it draws bundles) and no extra
// pass needs the mesh strategies' pass targets; never otherwise.
BatchStrategy batchStrategyFor(const BatchOptions& options, std::span<gpu::Context* const> devices);

}  // namespace encore::batch
