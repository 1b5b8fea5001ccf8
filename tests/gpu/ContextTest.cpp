#include <gtest/gtest.h>

#include <cstring>

#include "GpuTestSupport.h"
#include "gpu/Readback.h"
#include "gpu/Upload.h"

namespace encore::gpu {
namespace {

TEST(ContextTest, AdapterIsVulkanAndNamed) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto& adapter = context->adapterDescription();
    EXPECT_FALSE(adapter.name.empty());
    EXPECT_NE(adapter.summary().find("Vulkan"), std::string::npos);
}

// A validation error must never pass silently: the context records it and checkNoErrors fails.
TEST(ContextTest, ValidationErrorsAreCaptured) {
    ENCORE_REQUIRE_VULKAN(context);
    ASSERT_TRUE(context->checkNoErrors("before").ok());
    wgpu::BufferDescriptor invalid{};
    invalid.size = 16;
    invalid.usage = wgpu::BufferUsage::MapRead | wgpu::BufferUsage::MapWrite;  // Not allowed.
    wgpu::Buffer buffer = context->device().CreateBuffer(&invalid);
    auto checked = context->checkNoErrors("Creating an invalid buffer");
    ASSERT_FALSE(checked.ok());
    EXPECT_EQ(checked.error().code, ErrorCode::ValidationError);
    EXPECT_NE(checked.error().message.find("Creating an invalid buffer raised 1 WebGPU error"),
              std::string::npos);
    EXPECT_TRUE(context->checkNoErrors("after").ok());
}

TEST(ContextTest, BufferRoundTrip) {
    ENCORE_REQUIRE_VULKAN(context);
    const std::vector<std::uint32_t> values = {1, 2, 3, 0xdeadbeef, 5};
    auto buffer = createBufferFrom<std::uint32_t>(context->device(), wgpu::BufferUsage::CopySrc,
                                                  values, "round trip");
    EXPECT_EQ(buffer.GetSize(), 20u);
    auto bytes = readBuffer(*context, buffer, 4, 12);
    ASSERT_TRUE(bytes.ok()) << bytes.error().message;
    std::vector<std::uint32_t> read(3);
    std::memcpy(read.data(), bytes->data(), 12);
    EXPECT_EQ(read, (std::vector<std::uint32_t>{2, 3, 0xdeadbeef}));
    EXPECT_FALSE(readBuffer(*context, buffer, 0, 24).ok());
    EXPECT_TRUE(context->checkNoErrors("round trip").ok());
}

// Benchmarks spin while they wait: every wait (idle, read-backs) still returns once the GPU is
// done, with the data it wrote, and the mode goes back to blocking.
TEST(ContextTest, SpinningWaitsSeeTheGpuFinish) {
    ENCORE_REQUIRE_VULKAN(context);
    ASSERT_EQ(context->waitMode(), WaitMode::Block);
    context->setWaitMode(WaitMode::Spin);
    const std::vector<std::uint32_t> values(4096, 7u);
    auto source = createBufferFrom<std::uint32_t>(context->device(), wgpu::BufferUsage::CopySrc,
                                                  values, "spin source");
    wgpu::BufferDescriptor descriptor{};
    descriptor.size = values.size() * sizeof(std::uint32_t);
    descriptor.usage = wgpu::BufferUsage::CopyDst | wgpu::BufferUsage::CopySrc;
    wgpu::Buffer copy = context->device().CreateBuffer(&descriptor);
    for (int round = 0; round < 3; ++round) {
        wgpu::CommandEncoder encoder = context->device().CreateCommandEncoder();
        encoder.CopyBufferToBuffer(source, 0, copy, 0, descriptor.size);
        wgpu::CommandBuffer commands = encoder.Finish();
        context->queue().Submit(1, &commands);
        context->waitForIdle();
    }
    auto bytes = readBuffer(*context, copy, 0, descriptor.size);
    context->setWaitMode(WaitMode::Block);
    ASSERT_TRUE(bytes.ok()) << bytes.error().message;
    std::vector<std::uint32_t> read(values.size());
    std::memcpy(read.data(), bytes->data(), descriptor.size);
    EXPECT_EQ(read, values);
    EXPECT_TRUE(context->checkNoErrors("spinning waits").ok());
}

}  // namespace
}  // namespace encore::gpu
