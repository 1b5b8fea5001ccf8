#pragma once

#include "render/strategies/NodeLoopStrategy.h"

namespace encore::render {

// The case study's Part 1, made to draw every model: one render pipeline per primitive; one
// uniform buffer and bind group per mesh node; every attribute accessor copied into its own
// tightly packed vertex buffer (so no accessor offset ever reaches a pipeline layout) and bound
// to its own slot. Loop: node -> primitive.
class NaiveStrategy final : public NodeLoopStrategy {
  public:
    StrategyKind kind() const override { return StrategyKind::Naive; }
    Result<void> prepare(const RenderSetup& setup, const GpuScene& scene) override;
};

}  // namespace encore::render
