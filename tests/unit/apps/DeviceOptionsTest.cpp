#include <gtest/gtest.h>

#include <vector>

#include "DeviceOptions.h"

namespace encore::app {
namespace {

gpu::AdapterDescription adapter(std::size_t index, wgpu::AdapterType type) {
    gpu::AdapterDescription description;
    description.index = index;
    description.name = "adapter " + std::to_string(index);
    description.backend = wgpu::BackendType::Vulkan;
    description.adapterType = type;
    return description;
}

// Two GPUs and lavapipe, as a GPU machine with Mesa lists them.
const std::vector<gpu::AdapterDescription> kMachine = {adapter(0, wgpu::AdapterType::DiscreteGPU),
                                                       adapter(1, wgpu::AdapterType::DiscreteGPU),
                                                       adapter(2, wgpu::AdapterType::CPU)};

TEST(DeviceOptionsTest, ParsesAnIndex) {
    EXPECT_EQ(parseDeviceIndex("0").value(), 0u);
    EXPECT_EQ(parseDeviceIndex("7").value(), 7u);
    for (const char* bad : {"", "-1", "one", "1x", " 1", "1,2"}) {
        auto parsed = parseDeviceIndex(bad);
        ASSERT_FALSE(parsed) << bad;
        EXPECT_EQ(parsed.error().code, ErrorCode::InvalidArgument);
        EXPECT_NE(parsed.error().message.find("not a device index"), std::string::npos);
    }
}

TEST(DeviceOptionsTest, AllMeansTheAdaptersLikeTheFirst) {
    EXPECT_EQ(parseDeviceList("all", kMachine).value(), (std::vector<std::size_t>{0, 1}));
    const std::vector<gpu::AdapterDescription> lavapipeOnly = {adapter(0, wgpu::AdapterType::CPU)};
    EXPECT_EQ(parseDeviceList("all", lavapipeOnly).value(), (std::vector<std::size_t>{0}));
    EXPECT_EQ(gpu::adaptersLike(kMachine, 2), (std::vector<std::size_t>{2}));
    EXPECT_TRUE(gpu::adaptersLike(kMachine, 3).empty());
}

TEST(DeviceOptionsTest, ListsIndicesInOrderWithRepeats) {
    EXPECT_EQ(parseDeviceList("1", kMachine).value(), (std::vector<std::size_t>{1}));
    EXPECT_EQ(parseDeviceList("2,0", kMachine).value(), (std::vector<std::size_t>{2, 0}));
    EXPECT_EQ(parseDeviceList("0,0,0", kMachine).value(), (std::vector<std::size_t>{0, 0, 0}));
}

TEST(DeviceOptionsTest, AnIndexPastTheAdaptersNamesHowManyThereAre) {
    auto parsed = parseDeviceList("0,3", kMachine);
    ASSERT_FALSE(parsed);
    EXPECT_EQ(parsed.error().code, ErrorCode::NoAdapter);
    EXPECT_NE(parsed.error().message.find("no device 3"), std::string::npos);
    EXPECT_NE(parsed.error().message.find("has 3 adapters"), std::string::npos);
    auto malformed = parseDeviceList("0,,1", kMachine);
    ASSERT_FALSE(malformed);
    EXPECT_EQ(malformed.error().code, ErrorCode::InvalidArgument);
}

}  // namespace
}  // namespace encore::app
