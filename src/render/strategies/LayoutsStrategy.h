#pragma once

#include "render/strategies/NodeLoopStrategy.h"

namespace encore::render {

// The case study's Part 2: vertex data bound where it lies (one buffer per bufferView, offsets
// moved into setVertexBuffer, interleaved attributes in one slot), still one pipeline per
// primitive and the node -> primitive loop of `naive`.
class LayoutsStrategy final : public NodeLoopStrategy {
  public:
    StrategyKind kind() const override { return StrategyKind::Layouts; }
    Result<void> prepare(const RenderSetup& setup, const GpuScene& scene) override;
};

}  // namespace encore::render
