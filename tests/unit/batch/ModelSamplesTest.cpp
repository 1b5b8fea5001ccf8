// The samples a batch makes of a model with KHR_materials_variants, their folder names, and
// whether they are finished, decided before the model loads.

#include <gtest/gtest.h>

#include <fstream>

#include "TestPaths.h"
#include "VariantFixture.h"
#include "batch/ModelOutput.h"
#include "batch/ModelSamples.h"

namespace encore::batch {
namespace {

namespace fs = std::filesystem;

TEST(ModelSamplesTest, VariantNamesBecomeSafeFolderNames) {
    EXPECT_EQ(
        variantSampleNames(
            "cars/shoe", std::vector<std::string>{"midnight", "beach ball", "a/b", "", "x.y-z_1"}),
        (std::vector<std::string>{"cars/shoe@midnight", "cars/shoe@beach_ball", "cars/shoe@a_b",
                                  "cars/shoe@variant", "cars/shoe@x.y-z_1"}));
    // Names that the rules make equal keep their index.
    EXPECT_EQ(variantSampleNames("m", std::vector<std::string>{"red", "r d", "r/d", "red"}),
              (std::vector<std::string>{"m@red-0", "m@r_d-1", "m@r_d-2", "m@red-3"}));
    EXPECT_EQ(variantSampleNames("m", std::vector<std::string>{"a-1", "a", "a"}),
              (std::vector<std::string>{"m@a-1", "m@a-1-1", "m@a-2"}));
    EXPECT_TRUE(variantSampleNames("m", {}).empty());
}

TEST(ModelSamplesTest, OneVariantAllOfThemOrNone) {
    const BatchInput input{"/models/shoe.glb", "shoe"};
    const std::vector<std::string> variants = {"midnight", "beach ball"};
    BatchOptions options;
    auto samples = modelSamples(options, input, variants);
    ASSERT_TRUE(samples.ok());
    ASSERT_EQ(samples->size(), 1u);
    EXPECT_EQ((*samples)[0].name, "shoe");
    EXPECT_FALSE((*samples)[0].variant.has_value());

    options.allVariants = true;
    samples = modelSamples(options, input, variants);
    ASSERT_TRUE(samples.ok());
    ASSERT_EQ(samples->size(), 3u);
    EXPECT_EQ((*samples)[1].name, "shoe@midnight");
    EXPECT_EQ((*samples)[2].name, "shoe@beach_ball");
    EXPECT_EQ((*samples)[2].variantName, "beach ball");
    EXPECT_EQ((*samples)[2].variant, scene::VariantId(1u));

    options.allVariants = false;
    options.variant = "1";
    samples = modelSamples(options, input, variants);
    ASSERT_TRUE(samples.ok());
    ASSERT_EQ(samples->size(), 1u);
    EXPECT_EQ((*samples)[0].name, "shoe@beach_ball");

    options.variant = "red";
    samples = modelSamples(options, input, variants);
    ASSERT_FALSE(samples.ok());
    EXPECT_EQ(samples.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(samples.error().message.find("'/models/shoe.glb' has no material variant 'red' "
                                           "(its variants: 0 'midnight', 1 'beach ball'"),
              std::string::npos)
        << samples.error().message;
}

// Every file of a finished one-view sample (modelFiles: the view, metadata.json, transforms.json).
void finish(const fs::path& output, const std::string& name) {
    const fs::path folder = modelFolder(output, name);
    fs::create_directories(folder);
    ModelFileSet files;
    files.views = 1;
    for (const fs::path& file : modelFiles(folder, files)) {
        std::ofstream(file) << "x";
    }
}

TEST(ModelSamplesTest, FinishedWhenEverySampleIs) {
    const fs::path dir = test::makeTempDir("model-samples");
    const BatchInput input{test::variantQuads().writeGlb(dir, "quads"), "quads"};
    BatchOptions options;
    options.output = dir / "out";
    options.views.views = 1;
    EXPECT_FALSE(samplesFinished(options, input));
    finish(options.output, "quads");
    EXPECT_TRUE(samplesFinished(options, input));

    options.allVariants = true;
    EXPECT_FALSE(samplesFinished(options, input));  // The variants' folders are missing.
    for (const char* name : {"quads@green", "quads@blue_paint", "quads@glass", "quads@textured"}) {
        finish(options.output, name);
    }
    EXPECT_TRUE(samplesFinished(options, input));

    options.allVariants = false;
    options.variant = "glass";
    EXPECT_TRUE(samplesFinished(options, input));
    options.variant = "no such variant";  // Not finished: the load reports it.
    EXPECT_FALSE(samplesFinished(options, input));
    // A file that cannot be read is never finished either.
    options.variant = "glass";
    EXPECT_FALSE(samplesFinished(options, {dir / "missing.glb", "quads"}));
}

}  // namespace
}  // namespace encore::batch
