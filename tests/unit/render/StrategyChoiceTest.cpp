#include <gtest/gtest.h>

#include <vector>

#include "encore/render/StrategyKind.h"

namespace encore::render {
namespace {

using Kind = StrategyKind;

// allStrategies() is derived from the list of names: every kind of the enumeration is in it once,
// in the enumeration's order, with a name of its own.
TEST(StrategyChoiceTest, EveryKindIsListedOnceWithItsOwnName) {
    const auto kinds = allStrategies();
    ASSERT_EQ(kinds.size(), std::size_t(Kind::Visibility) + 1);
    for (std::size_t i = 0; i < kinds.size(); ++i) {
        EXPECT_EQ(kinds[i], Kind(i));
        EXPECT_NE(strategyName(kinds[i]), "unknown");
        for (std::size_t j = 0; j < i; ++j) {
            EXPECT_NE(strategyName(kinds[i]), strategyName(kinds[j]));
        }
    }
}

TEST(StrategyChoiceTest, KindsWithABundledKindOfTheirOwnAreBundledByNamingIt) {
    EXPECT_EQ(StrategyChoice::of(Kind::Materials, true), (StrategyChoice{Kind::Bundles, false}));
    EXPECT_EQ(StrategyChoice::of(Kind::GpuCulling, true),
              (StrategyChoice{Kind::GpuCullingBundles, false}));
    EXPECT_EQ(StrategyChoice::of(Kind::Bundles, true), (StrategyChoice{Kind::Bundles, false}));
    EXPECT_EQ(StrategyChoice::of(Kind::Naive, true), (StrategyChoice{Kind::Naive, true}));
    EXPECT_EQ(StrategyChoice::of(Kind::Materials, false), (StrategyChoice{Kind::Materials, false}));
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
    for (const char* name : {"bundles+bundle", "materials+bundle", "gpu-culling+bundle", "+bundle",
                             "naive+", "naive+bundles", "Naive", ""}) {
        EXPECT_FALSE(strategyChoiceFromName(name).has_value()) << name;
    }
}

TEST(StrategyChoiceTest, TheBundlingAxisFollowsEachChoiceWithItsBundledFormOnce) {
    const std::vector<StrategyChoice> selection = {{Kind::Naive, false},
                                                   {Kind::Materials, false},
                                                   {Kind::Bundles, false},
                                                   {Kind::Naive, false},
                                                   {Kind::Layouts, true}};
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
