#pragma once

// The device feature the `visibility` strategy needs, and how a context asks for it.

#include <webgpu/webgpu_cpp.h>

#include "encore/gpu/Context.h"

namespace encore::render {

// 64-bit atomic min/max on vec2u in storage buffers (WGSL `enable atomic_vec2u_min_max;`): the
// visibility buffer's depth-and-id writes.
inline constexpr wgpu::FeatureName kVisibilityFeature = wgpu::FeatureName::AtomicVec2uMinMax;

// Asks for kVisibilityFeature where the adapter has it, with the allow_unsafe_apis toggle that
// Dawn offers it under. The apps, the Python module and the test context call it, so that the
// strategy can be chosen; without the feature the strategy refuses with an error naming it.
void requestVisibilityFeatures(gpu::ContextOptions& options);

}  // namespace encore::render
