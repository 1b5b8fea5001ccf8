#pragma once

// What strategies keep from one Renderer::prepare to the next (RendererOptions::keepPipelines,
// RenderSetup::keptObjects): GPU objects that depend on the renderer's setup and target, not on
// the scene, made by the first strategy that needs them and reused by every later one. One
// strategy is prepared at a time, so one holder serves them in turn.

#include <memory>

#include "render/visibility/VisibilityPipelines.h"
#include "render/visibility/VisibilityTarget.h"
#include "render/visibility/VisibilityWorkBuffers.h"

namespace encore::render {

class KeptStrategyObjects {
  public:
    std::unique_ptr<VisibilityPipelines> visibilityPipelines;
    VisibilityTarget visibilityTarget;
    VisibilityWorkBuffers visibilityWork;  // Grown, never shrunk, with the scenes.
};

}  // namespace encore::render
