#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "batch/BatchOptionsValidation.h"
#include "encore/image/HdrImage.h"

namespace encore::batch {
namespace {

using render::StrategyChoice;
using render::StrategyKind;

// Whether `options` fail with InvalidArgument and a message that contains `phrase`.
::testing::AssertionResult rejected(const BatchOptions& options, const std::string& phrase) {
    auto checked = validateBatchOptions(options);
    if (checked) {
        return ::testing::AssertionFailure() << "the options were accepted";
    }
    if (checked.error().code != ErrorCode::InvalidArgument) {
        return ::testing::AssertionFailure() << "not InvalidArgument: " << checked.error().message;
    }
    if (checked.error().message.find(phrase) == std::string::npos) {
        return ::testing::AssertionFailure()
               << "'" << checked.error().message << "' does not say '" << phrase << "'";
    }
    return ::testing::AssertionSuccess();
}

TEST(BatchOptionsValidationTest, AcceptsTheDefaults) {
    EXPECT_TRUE(validateBatchOptions(BatchOptions{}).ok());
}

TEST(BatchOptionsValidationTest, AcceptsTheSmallestBatch) {
    BatchOptions options;
    options.width = 1;
    options.height = 1;
    options.views.views = 1;
    options.renderers = 1;
    EXPECT_TRUE(validateBatchOptions(options).ok());
    options.renderers = kMaxRenderers;
    EXPECT_TRUE(validateBatchOptions(options).ok());
}

TEST(BatchOptionsValidationTest, RejectsNoPixelsOrNoViews) {
    const std::string phrase = "at least one view of at least one pixel";
    BatchOptions options;
    options.width = 0;
    EXPECT_TRUE(rejected(options, phrase));
    options = {};
    options.height = 0;
    EXPECT_TRUE(rejected(options, phrase));
    options = {};
    options.views.views = 0;
    EXPECT_TRUE(rejected(options, phrase));
}

TEST(BatchOptionsValidationTest, RejectsAFieldOfViewOutsideTheOpenRange) {
    BatchOptions options;
    for (float degrees : {0.0f, -10.0f, 180.0f, 200.0f, std::numeric_limits<float>::quiet_NaN()}) {
        options.views.horizontalFovDegrees = degrees;
        EXPECT_TRUE(rejected(options, "must lie in (0, 180)")) << degrees;
    }
    options.views.horizontalFovDegrees = 179.0f;
    EXPECT_TRUE(validateBatchOptions(options).ok());
}

TEST(BatchOptionsValidationTest, RejectsADistanceThatIsNotPositive) {
    BatchOptions options;
    for (float distance : {0.0f, -1.0f, std::numeric_limits<float>::quiet_NaN()}) {
        options.views.distance = distance;
        EXPECT_TRUE(rejected(options, "must be positive")) << distance;
    }
    options.views.distance = 0.01f;
    EXPECT_TRUE(validateBatchOptions(options).ok());
}

TEST(BatchOptionsValidationTest, RangesNeedTheirMinimumFirstAndValidEnds) {
    BatchOptions options;
    options.views.distance = ValueRange(1.5f, 2.2f);
    options.views.horizontalFovDegrees = ValueRange(30.0f, 60.0f);
    EXPECT_TRUE(validateBatchOptions(options).ok());
    options.views.distance = ValueRange(2.2f, 1.5f);
    EXPECT_TRUE(rejected(options,
                         "camera distance (2.2 to 1.5) must be positive, a range with "
                         "its minimum first"));
    options.views.distance = ValueRange(0.0f, 1.5f);
    EXPECT_TRUE(rejected(options, "must be positive"));
    options.views.distance = ValueRange(1.0f, std::numeric_limits<float>::infinity());
    EXPECT_TRUE(rejected(options, "must be positive"));
    options.views.distance = 1.5f;
    options.views.horizontalFovDegrees = ValueRange(60.0f, 30.0f);
    EXPECT_TRUE(rejected(options, "field of view (60 to 30 degrees) must lie in (0, 180)"));
    options.views.horizontalFovDegrees = ValueRange(10.0f, 180.0f);
    EXPECT_TRUE(rejected(options, "must lie in (0, 180)"));
}

TEST(BatchOptionsValidationTest, JitterLiesWithinHalfATurn) {
    BatchOptions options;
    for (float degrees : {-1.0f, 181.0f, std::numeric_limits<float>::quiet_NaN()}) {
        options.views.jitterDegrees = degrees;
        EXPECT_TRUE(rejected(options, "camera jitter")) << degrees;
    }
    options.views.jitterDegrees = 180.0f;
    EXPECT_TRUE(validateBatchOptions(options).ok());
}

TEST(BatchOptionsValidationTest, EnvironmentRangesAndSources) {
    BatchOptions options;
    options.lighting.intensity = ValueRange(0.5f, 2.0f);
    options.lighting.rotationDegrees = ValueRange(0.0f, 360.0f);
    EXPECT_TRUE(validateBatchOptions(options).ok());
    options.lighting.intensity = ValueRange(-1.0f, 2.0f);
    EXPECT_TRUE(rejected(options, "environment intensity (-1 to 2) must be 0 or more"));
    options.lighting.intensity = ValueRange(2.0f, 1.0f);
    EXPECT_TRUE(rejected(options, "minimum first"));
    options.lighting.intensity.reset();
    options.lighting.rotationDegrees = ValueRange(90.0f, 10.0f);
    EXPECT_TRUE(rejected(options, "environment rotation (90 to 10 degrees)"));
    options.lighting.rotationDegrees = std::numeric_limits<float>::quiet_NaN();
    EXPECT_TRUE(rejected(options, "must be finite"));
    options.lighting.rotationDegrees.reset();
    options.lighting.environmentDirectory = "skies";
    EXPECT_TRUE(validateBatchOptions(options).ok());  // The folder is listed when the batch runs.
    options.renderer.environmentImage =
        std::make_shared<image::HdrImage>(image::makeUniformEnvironment(1.0f, 1.0f, 1.0f));
    EXPECT_TRUE(rejected(options, "exclude each other"));
}

TEST(BatchOptionsValidationTest, LevelsOfDetailNeedANonNegativeErrorAndGpuCulling) {
    BatchOptions options;
    options.lodErrorPixels = -1.0f;
    EXPECT_TRUE(rejected(options, "need a non-negative error"));
    options.lodErrorPixels = std::numeric_limits<float>::quiet_NaN();
    EXPECT_TRUE(rejected(options, "need a non-negative error"));

    // Without a strategy the batch picks one that culls on the GPU.
    options.lodErrorPixels = 1.0f;
    EXPECT_TRUE(validateBatchOptions(options).ok());
    options.strategy = StrategyChoice::of(StrategyKind::GpuCulling, false);
    EXPECT_TRUE(validateBatchOptions(options).ok());
    options.strategy = StrategyChoice::of(StrategyKind::Visibility, false);
    EXPECT_TRUE(validateBatchOptions(options).ok());
    // A strategy that draws everything cannot choose levels; the error names it.
    options.strategy = StrategyChoice::of(StrategyKind::Bundles, false);
    EXPECT_TRUE(rejected(options, "(not " + render::strategyChoiceName(*options.strategy) + ")"));
    // Full detail goes with any strategy.
    options.lodErrorPixels = 0.0f;
    EXPECT_TRUE(validateBatchOptions(options).ok());
}

TEST(BatchOptionsValidationTest, RejectsRendererCountsOutsideTheRange) {
    BatchOptions options;
    options.renderers = 0;
    EXPECT_TRUE(rejected(options, "renderers (asked for 0)"));
    options.renderers = kMaxRenderers + 1;
    EXPECT_TRUE(rejected(options, "A batch takes 1 to " + std::to_string(kMaxRenderers)));
}

TEST(BatchOptionsValidationTest, DefaultStrategyFollowsLevelsOfDetail) {
    BatchOptions options;
    EXPECT_EQ(batchStrategy(options), StrategyChoice::of(StrategyKind::Bundles, false));
    options.lodErrorPixels = 2.0f;
    EXPECT_EQ(batchStrategy(options), StrategyChoice::of(StrategyKind::GpuCullingBundles, false));
    options.strategy = StrategyChoice::of(StrategyKind::Naive, true);
    EXPECT_EQ(batchStrategy(options), StrategyChoice::of(StrategyKind::Naive, true));
}

TEST(BatchOptionsValidationTest, AVisibilityLineNeedsTheAutomaticChoice) {
    BatchOptions options;
    EXPECT_TRUE(options.chooseStrategyPerModel);  // The default.
    options.visibilityFromTriangles = 5000;
    EXPECT_TRUE(validateBatchOptions(options).ok());
    options.strategy = StrategyChoice::of(StrategyKind::Bundles, false);
    EXPECT_TRUE(rejected(options,
                         "(5000) applies to the automatic choice only (--strategy auto), "
                         "not to bundles"));
    options.strategy.reset();
    options.chooseStrategyPerModel = false;
    EXPECT_TRUE(rejected(options,
                         "(5000) applies to the automatic choice only (--strategy auto), "
                         "not to bundles"));
}

TEST(BatchOptionsValidationTest, AutoLineFollowsTheSampleCount) {
    EXPECT_EQ(autoVisibilityTriangles(4), kAutoVisibilityTriangles);
    EXPECT_EQ(autoVisibilityTriangles(1), kAutoVisibilityTrianglesOneSample);
    EXPECT_GT(kAutoVisibilityTrianglesOneSample, kAutoVisibilityTriangles);
}

TEST(BatchOptionsValidationTest, RejectsOneVariantTogetherWithAll) {
    BatchOptions options;
    options.variant = "beach";
    EXPECT_TRUE(validateBatchOptions(options).ok());
    options.allVariants = true;
    EXPECT_TRUE(rejected(options, "one material variant ('beach') or all of them, not both"));
}

// Segmentation ids are drawn at either sample count (one sample's id per pixel at 4); albedo,
// material and ids come from the mesh shader of the materials-based strategies; an EXR depth
// format needs depth images.
TEST(BatchOptionsValidationTest, RejectsPassesThatCannotBeDrawn) {
    BatchOptions options;
    options.images.segmentation = true;
    ASSERT_EQ(options.samples, 4u);
    EXPECT_TRUE(validateBatchOptions(options).ok());
    options.samples = 1;
    EXPECT_TRUE(validateBatchOptions(options).ok());
    options.strategy = StrategyChoice::of(StrategyKind::Visibility, false);
    EXPECT_TRUE(rejected(options, "draws glTF materials in its mesh shader"));
    options.images = {.albedo = true};
    options.strategy = StrategyChoice::of(StrategyKind::Naive, false);
    EXPECT_TRUE(rejected(options, "not naive"));
    options.strategy = StrategyChoice::of(StrategyKind::GpuCulling, false);
    EXPECT_TRUE(validateBatchOptions(options).ok());

    BatchOptions exr;
    exr.images.depthFormat = DepthFormat::Exr;
    EXPECT_TRUE(rejected(exr, "add --depth"));
    exr.images.depth = true;
    EXPECT_TRUE(validateBatchOptions(exr).ok());
}

}  // namespace
}  // namespace encore::batch
