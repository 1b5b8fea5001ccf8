#include "RenderTestSupport.h"

#include <cstdio>
#include <cstring>

#include <gtest/gtest.h>

#include "GpuTestSupport.h"
#include "encore/image/HdrImage.h"
#include "gpu/Readback.h"

namespace encore::test {

std::shared_ptr<render::Environment> testEnvironment() {
    static std::shared_ptr<render::Environment> environment = [] {
        gpu::Context* context = vulkanContext();
        if (!context) {
            return std::shared_ptr<render::Environment>();
        }
        // The library must outlive the environment's later load() calls.
        static shaders::ShaderLibrary shaders(context->device());
        auto created = render::Environment::create(context->device(), context->queue(), shaders,
                                                   image::makeStudioEnvironment(256),
                                                   testEnvironmentOptions());
        if (!created) {
            std::fprintf(stderr, "%s\n", created.error().message.c_str());
            return std::shared_ptr<render::Environment>();
        }
        return std::make_shared<render::Environment>(std::move(*created));
    }();
    return environment;
}

render::EnvironmentOptions testEnvironmentOptions() {
    render::EnvironmentOptions options;
    options.specularSize = 64;
    options.irradianceSize = 16;
    options.lutSize = 64;
    options.specularSamples = 64;
    options.irradianceSamples = 128;
    return options;
}

render::RendererOptions pixelTestOptions(std::uint32_t width,
                                         std::uint32_t height,
                                         std::uint32_t samples,
                                         render::DebugChannel channel) {
    render::RendererOptions options;
    options.target = {width, height, samples};
    options.environment = testEnvironment();
    options.toneMapping.toneMapping = render::ToneMapping::None;
    options.lighting.debugChannel = channel;
    // Levels of detail change pixels by design; tests that compare strategies pixel for pixel
    // draw every instance at full detail (occlusion culling stays on: it must change nothing).
    options.culling.levelsOfDetail = false;
    return options;
}

CulledCounts culledCountsByLevel(gpu::Context& context, const render::GpuCuller& culler) {
    using render::GpuCuller;
    static_assert(GpuCuller::kPhases == 2);
    auto bytes = gpu::readBuffer(context, culler.indirectArguments(), 0,
                                 culler.indirectArguments().GetSize());
    EXPECT_TRUE(bytes.ok()) << bytes.error().message;
    CulledCounts counts;
    for (std::size_t draw = 0; draw < culler.draws().size() && bytes.ok(); ++draw) {
        auto& levels = counts.emplace_back(culler.draws()[draw].levelCount());
        for (std::uint32_t level = 0; level < levels.size(); ++level) {
            for (std::uint32_t phase = 0; phase < GpuCuller::kPhases; ++phase) {
                std::uint32_t words[5];
                std::memcpy(words, bytes->data() + culler.argumentsOffset(draw, level, phase),
                            sizeof(words));
                EXPECT_EQ(words[4], 0u) << "firstInstance must stay 0 (draw " << draw << ")";
                levels[level][phase] = words[1];
            }
        }
    }
    return counts;
}

std::vector<std::uint32_t> culledInstanceCounts(gpu::Context& context,
                                                const render::GpuCuller& culler) {
    std::vector<std::uint32_t> counts;
    for (const auto& levels : culledCountsByLevel(context, culler)) {
        std::uint32_t count = 0;
        for (const auto& phases : levels) {
            count += phases[0] + phases[1];
        }
        counts.push_back(count);
    }
    return counts;
}

}  // namespace encore::test
