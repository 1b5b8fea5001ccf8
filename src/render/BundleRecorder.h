#pragma once

// Records draw commands into a wgpu::RenderBundle through the same RenderEncoder interface that
// records into render passes, so one piece of recording code serves both. Bundles are created
// compatible with the setup's colour format, depth format and sample count, carry a label, and
// remember what was recorded into them.

#include <webgpu/webgpu_cpp.h>

#include <array>
#include <string>
#include <utility>

#include "encore/render/RendererStats.h"
#include "render/RenderEncoder.h"
#include "render/RenderSetup.h"
#include "render/SceneColorTargets.h"

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
    // A scene pass with pass targets has five colour targets of one format (PassTargets.h).
    const std::array<wgpu::TextureFormat, kMaxSceneColorTargets> formats = {
        setup.colorFormat, setup.colorFormat, setup.colorFormat, setup.colorFormat,
        setup.colorFormat};
    descriptor.colorFormatCount = setup.passTargets != 0 ? kMaxSceneColorTargets : 1;
    descriptor.colorFormats = formats.data();
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
