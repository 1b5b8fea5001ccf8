#pragma once

// The device feature the `visibility` strategy needs.

#include <webgpu/webgpu_cpp.h>

#include "encore/render/Renderer.h"  // requestVisibilityFeatures

namespace encore::render {

// 64-bit atomic min/max on vec2u in storage buffers (WGSL `enable atomic_vec2u_min_max;`): the
// visibility buffer's depth-and-id writes.
inline constexpr wgpu::FeatureName kVisibilityFeature = wgpu::FeatureName::AtomicVec2uMinMax;

// requestVisibilityFeatures (Renderer.h) asks for it where the adapter has it, with the
// allow_unsafe_apis toggle that Dawn offers it under.

}  // namespace encore::render
