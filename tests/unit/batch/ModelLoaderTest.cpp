#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <future>
#include <thread>

#include "GltfBuilder.h"
#include "TestPaths.h"
#include "TextureFixtures.h"
#include "batch/ModelLoader.h"
#include "core/FileIO.h"
#include "scene/LoadBudget.h"
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

// Models whose bytes are their images: `images` entries of one 128x128 PNG (64 KiB decoded each).
std::vector<BatchInput> imageModels(const std::string& name, int count, int images) {
    const fs::path dir = test::makeTempDir(name);
    EXPECT_TRUE(writeFile(dir / "tile.png",
                          test::encodePngBytes(test::solidImage({10, 20, 30, 255}, 128, 128)))
                    .ok());
    std::vector<BatchInput> inputs;
    for (int i = 0; i < count; ++i) {
        test::GltfBuilder builder;
        const auto positions = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
        builder.addScene({builder.addNode({.mesh = builder.addMesh({{{"POSITION", positions}}})})});
        for (int image = 0; image < images; ++image) {
            builder.json()["images"].push_back({{"uri", "tile.png"}});
        }
        const std::string model = "m" + std::to_string(i);
        inputs.push_back({builder.writeGltf(dir, model), model});
    }
    return inputs;
}

// The limit is shared by the scenes loaded ahead and the loads in progress: eight threads loading
// models of 512 KiB against a limit of 1 MiB wait for room instead of holding 4 MiB at once. The
// oldest load running always goes on and the scenes loaded ahead of it wait to be taken in
// order, so the most held at any check stays within twice the limit and an image per thread.
TEST(ModelLoaderTest, LoadsInProgressShareTheMemoryLimit) {
    constexpr std::uint64_t kImageBytes = 128 * 128 * 4;
    const auto inputs = imageModels("model-loader-budget", 16, 8);
    constexpr std::uint64_t kLimit = std::uint64_t{1} << 20;
    ThreadPool pool(8);
    ModelLoader loader(pool, inputs, {}, kLimit, 8);
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        auto loaded = takeWithin(loader);
        ASSERT_TRUE(loaded);
        ASSERT_TRUE(loaded->scene.ok()) << loaded->scene.error().message;
        EXPECT_GE(loaded->bytes, 8 * kImageBytes);
        loader.release(loaded->bytes);
    }
    EXPECT_EQ(loader.finish(), 0u);
    EXPECT_GT(loader.budgetWaits(), 0u);
    EXPECT_GT(loader.peakBytes(), kLimit / 2);
    EXPECT_LE(loader.peakBytes(), 2 * kLimit + 8 * (kImageBytes + 1024));
}

// Loads waiting for memory leave one of the pool's threads to its other tasks: two loads of
// 512 KiB on a pool of two threads, with two scenes loaded ahead against a limit of 1.25 MiB,
// would both wait for the taker, and a taker that waits for the pool (as a batch's device thread
// waits for its encodes) before it releases a scene would wait for ever.
TEST(ModelLoaderTest, LoadsWaitingForMemoryLeaveAThreadToThePool) {
    constexpr std::uint64_t kModelBytes = 8 * 128 * 128 * 4;
    const auto inputs = imageModels("model-loader-free-thread", 6, 8);
    std::promise<void> ran;  // Outlives the pool, which may run the task late.
    ThreadPool pool(2);
    ModelLoader loader(pool, inputs, {}, kModelBytes * 5 / 2, 2);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (loader.budgetWaits() == 0 && std::chrono::steady_clock::now() < deadline) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    ASSERT_GT(loader.budgetWaits(), 0u);
    auto held = takeWithin(loader);
    ASSERT_TRUE(held && held->scene.ok());
    pool.submit([&ran] { ran.set_value(); });
    EXPECT_EQ(ran.get_future().wait_for(std::chrono::seconds(20)), std::future_status::ready)
        << "every pool thread waits for memory";
    loader.release(held->bytes);
    for (std::size_t i = 1; i < inputs.size(); ++i) {
        auto loaded = takeWithin(loader);
        ASSERT_TRUE(loaded && loaded->scene.ok());
        loader.release(loaded->bytes);
    }
    EXPECT_EQ(loader.finish(), 0u);
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
        EXPECT_EQ(loaded->bytes, scene::decodedBytes(*loaded->scene));
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
