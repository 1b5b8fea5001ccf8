#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <future>

#include "TestPaths.h"
#include "batch/ModelLoader.h"
#include "core/FileIO.h"
#include "scene/SceneGenerator.h"

namespace encore::batch {
namespace {

namespace fs = std::filesystem;

std::vector<BatchInput> generatedInputs(const std::string& name, int count) {
    const fs::path dir = test::makeTempDir(name);
    std::vector<BatchInput> inputs;
    for (int i = 0; i < count; ++i) {
        scene::GeneratorOptions options;
        options.objectCount = 10;
        options.seed = std::uint32_t(i + 1);
        auto glb = scene::generateSceneGlb(options);
        EXPECT_TRUE(glb.ok());
        const fs::path path = dir / ("m" + std::to_string(i) + ".glb");
        EXPECT_TRUE(writeFile(path, *glb).ok());
        inputs.push_back({path, "m" + std::to_string(i)});
    }
    inputs.push_back({dir / "absent.glb", "absent"});
    return inputs;
}

// take() within a few seconds, or a failure instead of a hung test.
std::optional<LoadedModel> takeWithin(ModelLoader& loader) {
    auto taken = std::async(std::launch::async, [&] { return loader.take(); });
    if (taken.wait_for(std::chrono::seconds(20)) != std::future_status::ready) {
        ADD_FAILURE() << "take() did not return: the loader stalled";
        loader.stop();
        std::abort();  // The async task would block the test's exit.
    }
    return taken.get();
}

TEST(ModelLoaderTest, LoadsInOrderAndReportsFailuresAsResults) {
    const auto inputs = generatedInputs("model-loader-order", 3);
    ThreadPool pool(2);
    ModelLoader loader(pool, inputs, {}, std::uint64_t{1} << 30, 2);
    for (std::size_t i = 0; i < 3; ++i) {
        auto loaded = takeWithin(loader);
        ASSERT_TRUE(loaded);
        EXPECT_EQ(loaded->order, i);
        ASSERT_TRUE(loaded->scene.ok()) << loaded->scene.error().message;
        EXPECT_GT(loaded->bytes, 0u);
        EXPECT_EQ(loaded->bytes, sceneBytes(*loaded->scene));
        loader.release(loaded->bytes);
    }
    auto absent = takeWithin(loader);
    ASSERT_TRUE(absent);
    ASSERT_FALSE(absent->scene.ok());
    EXPECT_NE(absent->scene.error().message.find("absent.glb"), std::string::npos);
    EXPECT_TRUE(loader.exhausted());
    EXPECT_FALSE(loader.take());
    loader.finish();
}

// Every scene is larger than the limit: the loader still hands over the next one while the GPU
// thread holds the previous one (it releases a scene only after preparing the next).
TEST(ModelLoaderTest, ModelsLargerThanTheLimitLoadOneAhead) {
    const auto inputs = generatedInputs("model-loader-limit", 3);
    ThreadPool pool(2);
    ModelLoader loader(pool, inputs, {}, 1, 2);
    std::optional<LoadedModel> held = takeWithin(loader);
    ASSERT_TRUE(held && held->scene.ok());
    for (std::size_t i = 1; i < 3; ++i) {
        std::optional<LoadedModel> next = takeWithin(loader);
        ASSERT_TRUE(next && next->scene.ok());
        EXPECT_EQ(next->order, i);
        loader.release(held->bytes);
        held = std::move(next);
    }
    loader.release(held->bytes);
    loader.finish();
}

// Several device threads take models as they load: each model goes to exactly one of them.
TEST(ModelLoaderTest, ThreadsTakingAsLoadedGetEveryModelOnce) {
    const auto inputs = generatedInputs("model-loader-as-loaded", 6);
    ThreadPool pool(2);
    ModelLoader loader(pool, inputs, {}, std::uint64_t{1} << 30, 3, ModelLoader::Order::AsLoaded);
    const auto takeAll = [&] {
        std::vector<std::size_t> taken;
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
        while (!loader.exhausted() && std::chrono::steady_clock::now() < deadline) {
            if (auto loaded = loader.tryTake()) {
                taken.push_back(loaded->order);
                loader.release(loaded->bytes);
            } else {
                loader.waitForNext(10);
            }
        }
        return taken;
    };
    auto first = std::async(std::launch::async, takeAll);
    auto second = std::async(std::launch::async, takeAll);
    std::vector<std::size_t> all = first.get();
    const std::vector<std::size_t> others = second.get();
    all.insert(all.end(), others.begin(), others.end());
    std::sort(all.begin(), all.end());
    // Six generated models and the absent file (a failed load is a model too).
    EXPECT_EQ(all, (std::vector<std::size_t>{0, 1, 2, 3, 4, 5, 6}));
    EXPECT_FALSE(loader.tryTake());
    loader.finish();
}

TEST(ModelLoaderTest, StopStartsNoMoreLoads) {
    const auto inputs = generatedInputs("model-loader-stop", 2);
    ThreadPool pool(1);
    ModelLoader loader(pool, inputs, {}, std::uint64_t{1} << 30, 1);
    loader.stop();
    EXPECT_TRUE(loader.exhausted());
    EXPECT_FALSE(loader.take());
    loader.finish();
}

}  // namespace
}  // namespace encore::batch
