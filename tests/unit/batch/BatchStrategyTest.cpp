// BatchStrategy::forModel: auto's choice of each model's strategy from what it draws.

#include "batch/BatchStrategy.h"

#include <gtest/gtest.h>

namespace encore::batch {
namespace {

BatchStrategy autoOnAGpu(std::uint64_t line, bool opaqueStatic) {
    BatchStrategy strategy;
    strategy.base = render::StrategyChoice::of(render::StrategyKind::Bundles, false);
    strategy.visibilityFromTriangles = line;
    strategy.visibilityForOpaqueStatic = opaqueStatic;
    return strategy;
}

TEST(BatchStrategyTest, ModelsFromTheLineAndOpaqueStaticOnesGoToVisibility) {
    const BatchStrategy fourSamples = autoOnAGpu(kAutoVisibilityTriangles, true);
    EXPECT_EQ(fourSamples.forModel(12, true).kind, render::StrategyKind::Visibility);
    EXPECT_EQ(fourSamples.forModel(12, false).kind, render::StrategyKind::Bundles);
    EXPECT_EQ(fourSamples.forModel(kAutoVisibilityTriangles, false).kind,
              render::StrategyKind::Visibility);

    const BatchStrategy oneSample = autoOnAGpu(kAutoVisibilityTrianglesOneSample, false);
    EXPECT_EQ(oneSample.forModel(12, true).kind, render::StrategyKind::Bundles);
    EXPECT_EQ(oneSample.forModel(kAutoVisibilityTrianglesOneSample, false).kind,
              render::StrategyKind::Visibility);

    const BatchStrategy never;  // An explicit strategy, or a CPU.
    EXPECT_FALSE(never.mayChooseVisibility());
    EXPECT_EQ(never.forModel(std::uint64_t{1} << 40, true).kind, never.base.kind);
}

// batchStrategyFor (here for no device, where nothing rules visibility out): the rule for opaque,
// static models at four samples only, and not beside an explicit line.
TEST(BatchStrategyTest, TheOpaqueStaticRuleIsAutosAtFourSamplesOnly) {
    BatchOptions options;
    options.samples = 4;
    EXPECT_TRUE(batchStrategyFor(options, {}).visibilityForOpaqueStatic);
    options.samples = 1;
    EXPECT_FALSE(batchStrategyFor(options, {}).visibilityForOpaqueStatic);
    options.samples = 4;
    options.visibilityFromTriangles = 5000;
    const BatchStrategy explicitLine = batchStrategyFor(options, {});
    EXPECT_FALSE(explicitLine.visibilityForOpaqueStatic);
    EXPECT_EQ(explicitLine.visibilityFromTriangles, 5000u);
    options.visibilityFromTriangles.reset();
    options.strategy = render::StrategyChoice::of(render::StrategyKind::Bundles, false);
    EXPECT_FALSE(batchStrategyFor(options, {}).mayChooseVisibility());
    EXPECT_FALSE(batchStrategyFor(options, {}).visibilityForOpaqueStatic);
}

}  // namespace
}  // namespace encore::batch
