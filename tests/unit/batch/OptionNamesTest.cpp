// The batch's name tables: each name gives its value and back, and a wrong name is an error that
// names the option and every name it takes (the CLI's and Python's messages).

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "batch/OptionNames.h"

namespace encore::batch {
namespace {

template <class Enum>
void expectRoundTrip(NameTable<Enum> table) {
    std::set<std::string_view> names;
    std::set<Enum> values;
    for (const NamedValue<Enum>& entry : table) {
        EXPECT_EQ(valueNamed(table, entry.name), entry.value) << entry.name;
        EXPECT_EQ(nameOf(table, entry.value), entry.name);
        names.insert(entry.name);
        values.insert(entry.value);
    }
    EXPECT_EQ(names.size(), table.size());  // No name or value twice.
    EXPECT_EQ(values.size(), table.size());
    EXPECT_FALSE(valueNamed(table, "no-such-name"));
}

TEST(OptionNamesTest, EveryNameGivesItsValueAndBack) {
    expectRoundTrip(cameraDistributionNames());
    expectRoundTrip(outputLayoutNames());
    expectRoundTrip(pngFilteringNames());
    expectRoundTrip(segmentationByNames());
    expectRoundTrip(depthFormatNames());
    expectRoundTrip(passNames());
    expectRoundTrip(pngCompressionNames());
    expectRoundTrip(toneMappingNames());
    expectRoundTrip(debugChannelNames());
    EXPECT_EQ(nameOf(passNames(), ViewImage::Color), "rgba");
    EXPECT_EQ(valueNamed(debugChannelNames(), "base-color"), render::DebugChannel::BaseColor);
    EXPECT_EQ(valueNamed(cameraDistributionNames(), "upper-hemisphere"),
              CameraDistribution::UpperHemisphere);
    EXPECT_EQ(nameOf(segmentationByNames(), SegmentationBy::Material), "material");
}

TEST(OptionNamesTest, AWrongNameNamesTheOptionAndWhatItTakes) {
    const auto parsed = parseNamed(cameraDistributionNames(), "cube", "camera_distribution");
    ASSERT_FALSE(parsed.ok());
    EXPECT_EQ(parsed.error().code, ErrorCode::InvalidArgument);
    EXPECT_EQ(parsed.error().message,
              "camera_distribution takes orbit, sphere, upper-hemisphere, hammersley or fibonacci "
              "(not 'cube').");
    EXPECT_EQ(*parseNamed(depthFormatNames(), "exr", "--depth-format"), DepthFormat::Exr);
    EXPECT_EQ(nameList({"a"}), "a");
    EXPECT_EQ(nameList({"a", "b"}), "a or b");
}

}  // namespace
}  // namespace encore::batch
