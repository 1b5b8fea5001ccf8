#include <gtest/gtest.h>

#include <vector>

#include "encore/render/Strategy.h"

namespace encore::render {
namespace {

using Kind = StrategyKind;

TEST(StrategyChoiceTest, KindsWithABundledKindOfTheirOwnAreBundledByNamingIt) {
    EXPECT_EQ(StrategyChoice::of(Kind::Materials, true), (StrategyChoice{Kind::Bundles, false}));
    EXPECT_EQ(StrategyChoice::of(Kind::GpuCulling, true),
              (StrategyChoice{Kind::GpuCullingBundles, false}));
    EXPECT_EQ(StrategyChoice::of(Kind::Bundles, true), (StrategyChoice{Kind::Bundles, false}));
    EXPECT_EQ(StrategyChoice::of(Kind::Naive, true), (StrategyChoice{Kind::Naive, true}));
    EXPECT_EQ(StrategyChoice::of(Kind::Materials, false),
              (StrategyChoice{Kind::Materials, false}));
}

TEST(StrategyChoiceTest, NamesRoundTripForEveryKindOnBothAxes) {
    for (auto kind : allStrategies()) {
        for (bool bundle : {false, true}) {
            const StrategyChoice choice = StrategyChoice::of(kind, bundle);
            const std::string name = strategyChoiceName(choice);
            SCOPED_TRACE(name);
            const auto parsed = strategyChoiceFromName(name);
            ASSERT_TRUE(parsed.has_value());
            EXPECT_EQ(*parsed, choice);
        }
    }
    EXPECT_EQ(strategyChoiceName({Kind::Naive, true}), "naive+bundle");
    EXPECT_EQ(strategyChoiceName({Kind::Materials, true}), "bundles");
    EXPECT_EQ(strategyChoiceName({Kind::GpuCulling, false}), "gpu-culling");
}

TEST(StrategyChoiceTest, NamesWithoutAFrameOfTheirOwnAreRefused) {
    for (const char* name : {"bundles+bundle", "materials+bundle", "gpu-culling+bundle",
                             "+bundle", "naive+", "naive+bundles", "Naive", ""}) {
        EXPECT_FALSE(strategyChoiceFromName(name).has_value()) << name;
    }
}

TEST(StrategyChoiceTest, TheBundlingAxisFollowsEachChoiceWithItsBundledFormOnce) {
    const std::vector<StrategyChoice> selection = {
        {Kind::Naive, false}, {Kind::Materials, false}, {Kind::Bundles, false},
        {Kind::Naive, false}, {Kind::Layouts, true}};
    EXPECT_EQ(withBundlingAxis(selection, false),
              (std::vector<StrategyChoice>{{Kind::Naive, false},
                                           {Kind::Materials, false},
                                           {Kind::Bundles, false},
                                           {Kind::Layouts, true}}));
    EXPECT_EQ(withBundlingAxis(selection, true),
              (std::vector<StrategyChoice>{{Kind::Naive, false},
                                           {Kind::Naive, true},
                                           {Kind::Materials, false},
                                           {Kind::Bundles, false},
                                           {Kind::Layouts, true}}));
}

}  // namespace
}  // namespace encore::render
