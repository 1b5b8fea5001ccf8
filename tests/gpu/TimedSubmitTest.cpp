// gpu::submitTimed: what the callback encodes is submitted, and a GpuTimer's passes are timed.

#include <gtest/gtest.h>

#include <chrono>

#include <cstring>
#include <vector>

#include "GpuTestSupport.h"
#include "gpu/GpuTimer.h"
#include "gpu/Readback.h"
#include "gpu/TimedSubmit.h"
#include "gpu/Upload.h"

namespace encore::gpu {
namespace {

TEST(TimedSubmitTest, SubmitsWhatTheCallbackEncodes) {
    ENCORE_REQUIRE_VULKAN(context);
    const std::vector<std::uint32_t> values = {3, 1, 4, 1, 5, 9, 2, 6};
    const wgpu::Buffer source = createBufferFrom<std::uint32_t>(
        context->device(), wgpu::BufferUsage::CopySrc, values, "timed submit source");
    const wgpu::Buffer copy =
        createBuffer(context->device(), wgpu::BufferUsage::CopyDst | wgpu::BufferUsage::CopySrc,
                     values.size() * 4, "timed submit copy");
    int calls = 0;
    const auto start = std::chrono::steady_clock::now();
    const SubmitTiming timing =
        submitTimed(*context, nullptr, [&](const wgpu::CommandEncoder& encoder) {
            ++calls;
            encoder.CopyBufferToBuffer(source, 0, copy, 0, values.size() * 4);
        });
    const double wall =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(calls, 1);
    // The parts lie within the call: encoding, then the submit.
    EXPECT_LE(timing.encodeMilliseconds + timing.submitMilliseconds, wall);
    EXPECT_GT(timing.encodeMilliseconds + timing.submitMilliseconds, 0.0);
    EXPECT_FALSE(timing.gpuMilliseconds) << "no timer, no GPU time";

    auto bytes = readBuffer(*context, copy, 0, values.size() * 4);
    ASSERT_TRUE(bytes.ok()) << bytes.error().message;
    std::vector<std::uint32_t> read(values.size());
    std::memcpy(read.data(), bytes->data(), bytes->size());
    EXPECT_EQ(read, values);
    EXPECT_TRUE(context->checkNoErrors("A timed submit").ok());
}

// With a timer, the passes given its timestamp writes are timed and read back by the time
// submitTimed returns, with the frame's span; a submission without timed passes has no GPU time.
TEST(TimedSubmitTest, TimesThePassesOfItsTimer) {
    ContextOptions options;
    options.timestamps = true;
    auto context = Context::create(options);
    ASSERT_TRUE(context.ok()) << context.error().message;
    ASSERT_EQ(context->adapterDescription().backend, wgpu::BackendType::Vulkan);
    std::optional<GpuTimer> timer = GpuTimer::create(*context);
    if (!timer) {
        GTEST_SKIP() << "The adapter has no timestamp queries.";
    }
    const wgpu::Buffer buffer =
        createBuffer(context->device(), wgpu::BufferUsage::CopyDst, 1024, "timed pass buffer");

    const SubmitTiming timed =
        submitTimed(*context, &*timer, [&](const wgpu::CommandEncoder& encoder) {
            wgpu::ComputePassDescriptor descriptor{};
            descriptor.timestampWrites = timer->nextPass("empty pass");
            encoder.BeginComputePass(&descriptor).End();
        });
    ASSERT_TRUE(timed.gpuMilliseconds);
    ASSERT_EQ(timer->lastPasses().size(), 1u);
    EXPECT_EQ(timer->lastPasses()[0].label, "empty pass");

    ASSERT_TRUE(timer->lastSpan());
    EXPECT_GE(*timer->lastSpan(), *timed.gpuMilliseconds);

    // The span runs to the end of the frame's commands: a 64 MiB clear after the timed pass is
    // in it, not in the sum of the passes.
    const wgpu::Buffer large = createBuffer(context->device(), wgpu::BufferUsage::CopyDst,
                                            std::uint64_t(64) << 20, "cleared after the pass");
    const SubmitTiming cleared =
        submitTimed(*context, &*timer, [&](const wgpu::CommandEncoder& encoder) {
            wgpu::ComputePassDescriptor descriptor{};
            descriptor.timestampWrites = timer->nextPass("empty pass");
            encoder.BeginComputePass(&descriptor).End();
            encoder.ClearBuffer(large);
        });
    ASSERT_TRUE(cleared.gpuMilliseconds);
    ASSERT_TRUE(timer->lastSpan());
    EXPECT_GT(*timer->lastSpan(), *cleared.gpuMilliseconds)
        << "a 64 MiB clear took no time between the pass and the frame's end";

    const SubmitTiming untimed =
        submitTimed(*context, &*timer,
                    [&](const wgpu::CommandEncoder& encoder) { encoder.ClearBuffer(buffer); });
    EXPECT_FALSE(untimed.gpuMilliseconds) << "no pass was timed";
    EXPECT_TRUE(context->checkNoErrors("Timed submits").ok());
}

}  // namespace
}  // namespace encore::gpu
