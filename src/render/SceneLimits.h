#pragma once

// Whether a scene's GPU buffers fit the device's limits, checked before a strategy creates any
// of them: a scene beyond maxBufferSize or maxStorageBufferBindingSize fails with an error
// naming the limit, the size and what needed it, never with a WebGPU validation error.
//
// Checked here, per strategy: vertex and index data (one buffer per bufferView, per repacked
// accessor, or per accessor copy for `naive`), the punctual lights' storage buffer, the instance
// transforms' storage buffer (instancing and later) and the material uniforms (materials and
// later). GpuCuller::create checks its own buffers (they depend on the draw grouping), and
// texture sizes are handled by downscaling (MaterialResources). Encore does not split an
// oversized buffer: every one of them is bound whole or at offsets WebGPU cannot exceed.

#include "encore/core/Result.h"
#include "encore/gpu/DeviceLimits.h"
#include "encore/render/StrategyKind.h"
#include "encore/scene/SceneData.h"

namespace encore::render {

Result<void> checkSceneWithinLimits(const gpu::DeviceLimits& limits,
                                    const scene::SceneData& scene,
                                    StrategyKind kind);

}  // namespace encore::render
