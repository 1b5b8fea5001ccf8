// AnimationPlayer::evaluate must not allocate once the player exists (thousands of characters
// are evaluated per frame later). Counts every operator new of this test binary while playing.

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "SceneTestUtils.h"
#include "TestPaths.h"
#include "encore/scene/AnimationPlayer.h"

namespace {
std::atomic<std::size_t> gAllocations{0};
}  // namespace

void* operator new(std::size_t size) {
    ++gAllocations;
    if (void* pointer = std::malloc(size == 0 ? 1 : size)) {
        return pointer;
    }
    throw std::bad_alloc();
}
void operator delete(void* pointer) noexcept {
    std::free(pointer);
}
void operator delete(void* pointer, std::size_t) noexcept {
    std::free(pointer);
}

namespace encore::scene {
namespace {

std::size_t allocationsWhilePlaying(AnimationPlayer& player, double duration) {
    player.evaluate(0.0);  // The first evaluation may touch everything; none allocates anyway.
    const std::size_t before = gAllocations.load();
    for (int frame = 0; frame < 240; ++frame) {
        player.evaluate(frame / 60.0 * (duration > 0.0 ? duration / 2.0 : 1.0));
    }
    player.evaluate(-1.0);  // A jump backwards: binary search, still no allocation.
    return gAllocations.load() - before;
}

TEST(AnimationAllocationTest, EvaluateDoesNotAllocate) {
    const auto dir = test::sharedModelsDir();
    if (!dir) {
        GTEST_SKIP() << "The shared sample models (../shared/models) are absent; skipping.";
    }
    for (const char* model : {"Fox/glTF-Binary/Fox.glb", "BrainStem/glTF-Binary/BrainStem.glb",
                              "AnimatedMorphCube/glTF-Binary/AnimatedMorphCube.glb",
                              "CesiumMilkTruck/glTF-Binary/CesiumMilkTruck.glb"}) {
        if (!std::filesystem::exists(*dir / model)) {
            continue;
        }
        const std::size_t beforeLoad = gAllocations.load();
        const auto scene = loadScene(*dir / model);
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        ASSERT_GT(gAllocations.load(), beforeLoad) << "the allocation counter counts nothing";
        AnimationPlayer player(*scene);
        EXPECT_EQ(allocationsWhilePlaying(player, player.duration()), 0u) << model;
        player.setMode(PlaybackMode::Loop);
        ASSERT_TRUE(player.select(AnimationId(0u)).ok());
        EXPECT_EQ(allocationsWhilePlaying(player, player.duration()), 0u) << model;
    }
}

}  // namespace
}  // namespace encore::scene
