#pragma once

// Records draw commands into a wgpu::RenderBundle through the same RenderEncoder interface that
// records into render passes, so one piece of recording code serves both. Bundles are created
// compatible with the setup's colour format, depth format and sample count, carry a label, and
// remember what was recorded into them.

#include <webgpu/webgpu_cpp.h>

#include <string>
#include <utility>

#include "encore/render/DrawCounters.h"
#include "encore/render/RenderEncoder.h"
#include "encore/render/RenderSetup.h"

namespace encore::render {

struct RecordedBundle {
    wgpu::RenderBundle bundle;
    DrawCounters contents;  // The calls recorded into it.
};

// Calls `record(RenderEncoder&)` on a fresh bundle encoder and finishes the bundle.
template <typename RecordFunction>
RecordedBundle recordBundle(const RenderSetup& setup,
                            const std::string& label,
                            RecordFunction&& record) {
    wgpu::RenderBundleEncoderDescriptor descriptor{};
    descriptor.label = label.c_str();
    descriptor.colorFormatCount = 1;
    descriptor.colorFormats = &setup.colorFormat;
    descriptor.depthStencilFormat = setup.depthFormat;
    descriptor.sampleCount = setup.sampleCount;
    wgpu::RenderBundleEncoder bundleEncoder = setup.device.CreateRenderBundleEncoder(&descriptor);
    RecordedBundle recorded;
    RenderEncoder encoder(bundleEncoder, recorded.contents);
    std::forward<RecordFunction>(record)(encoder);
    wgpu::RenderBundleDescriptor finish{};
    finish.label = label.c_str();
    recorded.bundle = bundleEncoder.Finish(&finish);
    return recorded;
}

}  // namespace encore::render
