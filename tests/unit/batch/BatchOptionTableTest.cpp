// The batch's one description of its options: every default is what BatchOptions holds, values
// reach the options they name, bad values and combinations are errors naming the option as the
// user's front spells it, and docs/batch.md's table is the one made from the description.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "TestPaths.h"
#include "batch/BatchOptionTable.h"
#include "batch/OptionValues.h"

namespace encore::batch {
namespace {

const BatchOptionDescription& option(std::string_view name) {
    const BatchOptionDescription* found = findBatchOption(name, OptionFront::CommandLine);
    if (!found) {
        std::string keyword(name);  // The Python-only ones, by their keyword.
        std::replace(keyword.begin(), keyword.end(), '-', '_');
        found = findBatchOption(keyword, OptionFront::Python);
    }
    EXPECT_NE(found, nullptr) << name;
    return *found;
}

Result<BatchOptions> applied(std::vector<std::pair<std::string, std::string>> values,
                             OptionFront front = OptionFront::CommandLine) {
    std::vector<GivenOption> given;
    for (const auto& [name, value] : values) {
        given.push_back({&option(name), value});
    }
    BatchOptions options;
    ENCORE_TRY(applyBatchOptions(options, given, front));
    return options;
}

// What the options that the table sets hold, written out, to compare two BatchOptions.
std::string fingerprint(const BatchOptions& o) {
    std::ostringstream s;
    s << o.width << 'x' << o.height << ' ' << o.samples << ' ' << o.views.views << ' '
      << int(o.views.distribution) << ' ' << o.views.elevationDegrees.min << ':'
      << o.views.elevationDegrees.max << ' ' << o.views.seed << ' ' << o.views.distance.min << ':'
      << o.views.distance.max << ' ' << o.views.horizontalFovDegrees.min << ' '
      << o.views.jitterDegrees << ' ' << o.views.normalize << ' ' << o.strategy.has_value()
      << o.chooseStrategyPerModel << ' ' << o.visibilityFromTriangles.has_value() << ' '
      << o.lodErrorPixels << ' ' << o.strict << ' ' << o.modelTimeoutSeconds << ' '
      << o.maxTextureSize << ' ' << o.allowUrisOutside << ' ' << o.variant << o.allVariants << ' '
      << o.jobs << ' ' << o.memoryLimitBytes << ' ' << o.renderers << ' ' << o.images.perView()
      << int(o.images.segmentationBy) << int(o.images.depthFormat) << int(o.images.drawing) << ' '
      << o.topLightLux << ' ' << int(o.pngCompression) << int(o.pngFiltering) << int(o.layout)
      << ' ' << o.shards << ' ' << o.shardBytes << ' ' << o.blankThreshold << ' '
      << o.writeFailureLog << ' ' << bool(o.renderer.environmentImage)
      << o.lighting.environmentDirectory << ' ' << o.lighting.rotationDegrees.has_value()
      << o.lighting.intensity.has_value() << ' ' << int(o.renderer.toneMapping.toneMapping) << ' '
      << o.renderer.toneMapping.exposure << ' ' << int(o.renderer.toneMapping.background) << ' '
      << o.renderer.lighting.imageBasedLighting << o.renderer.lighting.punctualLights << ' '
      << int(o.renderer.lighting.debugChannel) << ' ' << o.views.azimuthsDegrees.size()
      << o.views.elevationsDegrees.size() << o.views.distances.size() << o.views.poses.size() << ' '
      << int(o.views.projection) << o.views.orthoScale << o.views.distanceRelativeToFov << ' '
      << o.cameraConvention.has_value() << o.preset;
    return s.str();
}

TEST(BatchOptionTableTest, EveryDefaultIsWhatBatchOptionsHolds) {
    const std::string defaults = fingerprint(BatchOptions{});
    std::size_t withDefault = 0;
    for (const BatchOptionDescription& description : batchOptionDescriptions()) {
        if (description.defaultValue.empty()) {
            continue;
        }
        ++withDefault;
        BatchOptions options;
        auto set = description.apply(options, description.defaultValue, description.name);
        ASSERT_TRUE(set) << description.name << ": " << set.error().message;
        EXPECT_EQ(fingerprint(options), defaults) << description.name;
    }
    EXPECT_GE(withDefault, 20u);
}

TEST(BatchOptionTableTest, NamesAreUniqueOnEachFront) {
    for (OptionFront front : {OptionFront::CommandLine, OptionFront::Python}) {
        const std::vector<std::string> names = batchOptionNames(front);
        EXPECT_EQ(std::set<std::string>(names.begin(), names.end()).size(), names.size());
        EXPECT_GE(names.size(), 45u);
    }
    EXPECT_EQ(option("memory-limit").pythonKeyword(), "memory_limit_mib");
    EXPECT_EQ(option("tonemap").pythonKeyword(), "tone_mapping");
    EXPECT_EQ(findBatchOption("strategy", OptionFront::Python), nullptr);  // The Renderer's.
    EXPECT_EQ(findBatchOption("failure-log", OptionFront::CommandLine), nullptr);
}

TEST(BatchOptionTableTest, ValuesReachTheOptionsTheyName) {
    auto options = applied({{"size", "640x480"},
                            {"samples", "1"},
                            {"random-views", "7"},
                            {"distance", "1.2:2.5"},
                            {"environment-rotation", "random"},
                            {"environment-intensity", "0.5"},
                            {"shard-size", "1GiB"},
                            {"memory-limit", "512"},
                            {"strategy", "visibility"},
                            {"segmentation", "true"},
                            {"segmentation-by", "material"},
                            {"no-normalize", "true"},
                            {"background", "#ff0000"},
                            {"png-filtering", "cpu"},
                            {"debug-channel", "normal"}});
    ASSERT_TRUE(options) << options.error().message;
    EXPECT_EQ(options->width, 640u);
    EXPECT_EQ(options->height, 480u);
    EXPECT_EQ(options->samples, 1u);
    EXPECT_EQ(options->views.views, 7u);
    EXPECT_EQ(options->views.distribution, CameraDistribution::Sphere);
    EXPECT_EQ(options->views.distance, ValueRange(1.2f, 2.5f));
    EXPECT_EQ(options->lighting.rotationDegrees, ValueRange(0.0f, 360.0f));
    EXPECT_EQ(options->lighting.intensity, ValueRange(0.5f));
    EXPECT_EQ(options->shardBytes, std::uint64_t{1} << 30);
    EXPECT_EQ(options->memoryLimitBytes, std::uint64_t{512} << 20);
    ASSERT_TRUE(options->strategy);
    EXPECT_EQ(options->strategy->kind, render::StrategyKind::Visibility);
    EXPECT_TRUE(options->images.segmentation);
    EXPECT_EQ(options->images.segmentationBy, SegmentationBy::Material);
    EXPECT_FALSE(options->views.normalize);
    EXPECT_EQ(options->renderer.toneMapping.background, render::BackgroundKind::Color);
    EXPECT_FLOAT_EQ(options->renderer.toneMapping.backgroundColor.r, 1.0f);
    EXPECT_EQ(options->renderer.toneMapping.backgroundColor.g, 0.0f);
    EXPECT_EQ(options->pngFiltering, PngFiltering::Cpu);
    EXPECT_EQ(options->renderer.lighting.debugChannel, render::DebugChannel::Normal);

    auto automatic = applied({{"strategy", "visibility"}, {"failure-log", "false"}});
    ASSERT_TRUE(automatic);
    EXPECT_FALSE(automatic->writeFailureLog);
}

TEST(BatchOptionTableTest, BadValuesNameTheOptionAsTheFrontSpellsIt) {
    const auto message = [](std::vector<std::pair<std::string, std::string>> values,
                            OptionFront front) {
        auto options = applied(std::move(values), front);
        EXPECT_FALSE(options);
        return options ? std::string() : options.error().message;
    };
    EXPECT_EQ(message({{"views", "0"}}, OptionFront::CommandLine),
              "--views takes a whole number from 1 to 10000 (not '0').");
    EXPECT_EQ(message({{"views", "0"}}, OptionFront::Python),
              "views takes a whole number from 1 to 10000 (not '0').");
    EXPECT_EQ(message({{"memory-limit", "0"}}, OptionFront::Python).substr(0, 22),
              "memory_limit_mib takes");
    EXPECT_EQ(message({{"camera-distribution", "cube"}}, OptionFront::Python),
              "camera_distribution takes orbit, sphere, upper-hemisphere, hammersley or fibonacci "
              "(not 'cube').");
    EXPECT_EQ(message({{"samples", "2"}}, OptionFront::CommandLine),
              "--samples takes 1 or 4 (not '2').");
    EXPECT_EQ(message({{"size", "0x5"}}, OptionFront::CommandLine),
              "--size takes W or WxH in pixels, each from 1 to 8192 (not '0x5').");
    EXPECT_EQ(message({{"camera-jitter", "200"}}, OptionFront::CommandLine),
              "--camera-jitter takes a number from 0 to 180 (not '200').");
    EXPECT_EQ(message({{"exposure", "-1"}}, OptionFront::CommandLine),
              "--exposure takes a number of at least 0 (not '-1').");
    EXPECT_EQ(message({{"distance", "far"}}, OptionFront::CommandLine),
              "--distance takes a number or a range MIN:MAX (not 'far').");
    EXPECT_EQ(message({{"shard-size", "12 parsecs"}}, OptionFront::CommandLine).substr(0, 18),
              "--shard-size takes");
    EXPECT_NE(message({{"strategy", "fastest"}}, OptionFront::CommandLine).find("visibility"),
              std::string::npos);
    EXPECT_EQ(message({{"random-views", "3"}, {"elevation", "10"}}, OptionFront::Python),
              "random_views and elevation exclude each other.");
    EXPECT_EQ(message({{"segmentation-by", "mesh"}}, OptionFront::CommandLine),
              "--segmentation-by requires --segmentation.");
    // A flag given off does not count as given.
    EXPECT_EQ(message({{"depth", "false"}, {"depth-format", "exr"}}, OptionFront::Python),
              "depth_format requires depth.");
    EXPECT_NE(message({{"environment-dir", "/no/such/folder"}}, OptionFront::CommandLine)
                  .find("is not a folder"),
              std::string::npos);
}

TEST(BatchOptionTableTest, TheNearestNameIsOfferedForATypo) {
    const std::vector<std::string> names = batchOptionNames(OptionFront::Python);
    EXPECT_EQ(nearestName("view", names), "views");
    EXPECT_EQ(nearestName("viwes", names), "views");
    EXPECT_EQ(nearestName("camera_distributon", names), "camera_distribution");
    EXPECT_EQ(nearestName("tone_maping", names), "tone_mapping");
    EXPECT_EQ(nearestName("zzzzzz", names), "");
}

TEST(BatchOptionTableTest, DocsTableIsTheDescription) {
    const std::filesystem::path docs = test::sourceDir() / "docs" / "batch.md";
    std::ifstream file(docs);
    ASSERT_TRUE(file) << docs;
    std::stringstream text;
    text << file.rdbuf();
    const std::string expected = batchOptionsMarkdown();
    const bool found = text.str().find(expected) != std::string::npos;
    if (!found) {
        const std::filesystem::path written =
            test::makeTempDir("batch-options") / "batch-options.md";
        std::ofstream(written) << expected;
        ADD_FAILURE() << "docs/batch.md's Options table is not the one the description makes: "
                         "replace it with "
                      << written;
    }
    // Every option appears in it by both its names.
    for (const BatchOptionDescription& description : batchOptionDescriptions()) {
        if (description.commandLine) {
            EXPECT_NE(text.str().find("--" + description.name + "`"), std::string::npos)
                << description.name;
        }
        if (description.python) {
            EXPECT_NE(text.str().find("`" + description.pythonKeyword() +
                                      (description.keywordNegated ? "=False`" : "`")),
                      std::string::npos)
                << description.name;
        }
    }
}

}  // namespace
}  // namespace encore::batch
