// batch::runBatch's pipeline: several renderers take the models in turn, so that the next model
// uploads while the GPU draws the previous ones (BatchOptions::renderers). That must change
// nothing but the time: every file is byte for byte what the sequential pipeline (one renderer,
// each model prepared after the previous one's views are read back) writes, and a bad model
// between good ones fails at its own stage while its neighbours render.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "BatchOutput.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "TestFiles.h"
#include "TestPaths.h"
#include "batch/BatchRenderer.h"
#include "encore/batch/Batch.h"
#include "render/GpuStage.h"
#include "scene/SceneGenerator.h"

namespace encore::batch {
namespace {

namespace fs = std::filesystem;

BatchOptions smallBatch(const fs::path& output) {
    BatchOptions options;
    options.output = output;
    options.width = 48;
    options.height = 40;
    options.views.views = 5;
    options.jobs = 2;
    return options;
}

// Shared models of different kinds (textured, skinned, blended, untextured) and generated
// scenes, in an order that makes both renderers prepare several of them.
std::vector<BatchInput> mixedCollection(const fs::path& dir) {
    std::vector<BatchInput> inputs;
    const auto models = test::sharedModelsDir();
    if (models) {
        for (const char* name : {"Duck", "Fox", "AlphaBlendModeTest", "BoxTextured"}) {
            const fs::path path = *models / name / "glTF-Binary" / (std::string(name) + ".glb");
            if (fs::exists(path)) {
                inputs.push_back({path, name});
            }
        }
    }
    for (std::uint32_t seed = 1; seed <= 3; ++seed) {
        const fs::path path = dir / ("generated" + std::to_string(seed) + ".glb");
        test::writeGeneratedScene(path, 4 + seed, seed);
        inputs.insert(inputs.begin() + std::min<std::size_t>(inputs.size(), 2 * seed - 1),
                      {path, "generated" + std::to_string(seed)});
    }
    return inputs;
}

TEST(BatchPipelineTest, OverlappedModelsWriteTheSameFilesAsSequentialOnes) {
    ENCORE_REQUIRE_VULKAN(context);
    const fs::path dir = test::makeTempDir("batch-pipeline-same");
    const std::vector<BatchInput> inputs = mixedCollection(dir);
    ASSERT_GE(inputs.size(), 5u);

    // One renderer (sequential), two and three (the default).
    std::map<std::string, std::string> written[4];
    for (const std::size_t renderers : {1, 2, 3}) {
        BatchOptions options = smallBatch(dir / ("renderers" + std::to_string(renderers)));
        options.renderer.environment = test::testEnvironment();
        options.images.normals = true;
        options.images.depth = true;
        options.renderers = renderers;
        auto summary = runBatch(*context, inputs, options);
        ASSERT_TRUE(summary.ok()) << summary.error().message;
        EXPECT_EQ(summary->rendered, inputs.size());
        EXPECT_EQ(summary->failed, 0u);
        for (const Failure& failure : summary->failures) {
            ADD_FAILURE() << failure.file << " (" << failure.stage << "): " << failure.error;
        }
        written[renderers] = test::batchOutputFiles(options.output);
    }
    // Per model: five views of colour, normals and depth, metadata.json and transforms.json.
    EXPECT_EQ(written[1].size(), inputs.size() * (5 * 3 + 2));
    for (const std::size_t renderers : {2, 3}) {
        ASSERT_EQ(written[renderers].size(), written[1].size()) << renderers << " renderers";
        for (const auto& [name, bytes] : written[1]) {
            const auto found = written[renderers].find(name);
            ASSERT_NE(found, written[renderers].end())
                << name << " is missing with " << renderers << " renderers";
            EXPECT_TRUE(found->second == bytes)
                << name << " differs between 1 and " << renderers << " renderers";
        }
    }
    EXPECT_TRUE(context->checkNoErrors("the batches").ok());
}

// The lane's pools (gpu/ResourcePool.h): a model whose kinds of textures and buffers earlier
// models left behind creates no GPU object and maps no fresh memory, as metadata.json's `gpu`
// records, and the files are those of the first time (BatchPipelineTest above: the same as with
// one renderer, whose pool is reused in another order).
TEST(BatchPipelineTest, ModelsInSteadyStateCreateNoGpuObjects) {
    ENCORE_REQUIRE_VULKAN(context);
    const fs::path dir = test::makeTempDir("batch-pipeline-created");
    const std::vector<BatchInput> kinds = mixedCollection(dir);
    std::vector<BatchInput> inputs;
    for (const char* round : {"first-", "second-", "third-"}) {
        for (const BatchInput& kind : kinds) {
            inputs.push_back({kind.path, round + kind.name});
        }
    }
    BatchOptions options = smallBatch(dir / "out");
    options.renderer.environment = test::testEnvironment();
    auto summary = runBatch(*context, inputs, options);
    ASSERT_TRUE(summary.ok()) << summary.error().message;
    EXPECT_EQ(summary->rendered, inputs.size());
    ASSERT_EQ(summary->devices.size(), 1u);
    const DeviceSummary& device = summary->devices.front();
    EXPECT_GT(device.gpuObjectsCreated, 0u);  // The first models fill the pools.
    EXPECT_GT(device.modelsCreatingGpuObjects, 0u);
    EXPECT_LE(device.modelsCreatingGpuObjects, 2 * kinds.size());

    std::uint64_t createdByFirst = 0;
    for (const BatchInput& kind : kinds) {
        for (const char* round : {"first-", "third-"}) {
            std::ifstream file(options.output / (round + kind.name) / "metadata.json");
            const nlohmann::json metadata = nlohmann::json::parse(file, nullptr, false);
            ASSERT_TRUE(metadata.is_object()) << round << kind.name;
            const std::uint64_t objects = metadata["gpu"]["objectsCreated"].get<std::uint64_t>();
            const std::uint64_t mapped = metadata["gpu"]["bytesMapped"].get<std::uint64_t>();
            if (std::string(round) == "first-") {
                createdByFirst += objects;
                continue;
            }
            EXPECT_EQ(objects, 0u) << kind.name << ", third time";
            EXPECT_EQ(mapped, 0u) << kind.name << ", third time";
        }
    }
    EXPECT_GT(createdByFirst, 0u);
    EXPECT_TRUE(context->checkNoErrors("steady-state batch").ok());
}

// A caller that runs many short batches on one device (encore.dask: a batch per task) keeps its
// BatchRenderer: the batches after the first start with its pools, staging buffers and passes,
// so their models create no GPU object and map no fresh memory either.
TEST(BatchPipelineTest, BatchesAfterTheFirstOnKeptRenderersCreateNoGpuObjects) {
    ENCORE_REQUIRE_VULKAN(context);
    const fs::path dir = test::makeTempDir("batch-pipeline-kept");
    const std::vector<BatchInput> kinds = mixedCollection(dir);
    BatchRenderer renderers(*context);
    BatchOptions options = smallBatch(dir / "out");
    options.renderer.environment = test::testEnvironment();
    for (const char* round : {"first-", "second-", "third-"}) {
        std::vector<BatchInput> inputs;
        for (const BatchInput& kind : kinds) {
            inputs.push_back({kind.path, round + kind.name});
        }
        auto summary = runBatch(renderers, inputs, options);
        ASSERT_TRUE(summary.ok()) << summary.error().message;
        ASSERT_EQ(summary->rendered, inputs.size()) << round;
        const DeviceSummary& device = summary->devices.front();
        if (std::string(round) == "third-") {
            EXPECT_EQ(device.gpuObjectsCreated, 0u);
            EXPECT_EQ(device.modelsCreatingGpuObjects, 0u);
            for (const BatchInput& input : inputs) {
                std::ifstream file(options.output / input.name / "metadata.json");
                const nlohmann::json metadata = nlohmann::json::parse(file, nullptr, false);
                ASSERT_TRUE(metadata.is_object()) << input.name;
                EXPECT_EQ(metadata["gpu"]["bytesMapped"].get<std::uint64_t>(), 0u) << input.name;
            }
        } else if (std::string(round) == "first-") {
            EXPECT_GT(device.gpuObjectsCreated, 0u);
        }
    }
    EXPECT_EQ(renderers.counts().renderers, 1u);
    EXPECT_TRUE(context->checkNoErrors("batches on kept renderers").ok());
}

std::string metadataString(const fs::path& folder, const char* key) {
    std::ifstream file(folder / "metadata.json");
    const nlohmann::json metadata = nlohmann::json::parse(file, nullptr, false);
    return metadata.is_object() && metadata.contains(key) ? metadata[key].dump() : "";
}

// --strategy auto (BatchOptions::chooseStrategyPerModel): bundles for every model on lavapipe, a
// CPU; with a triangle line, visibility for the models from it and bundles below, each model's
// files those of the strategy it got when it draws every model, and metadata.json naming it.
TEST(BatchPipelineTest, AutoDrawsTheModelsFromItsLineWithVisibility) {
    ENCORE_REQUIRE_VULKAN(context);
    if (!context->device().HasFeature(wgpu::FeatureName::AtomicVec2uMinMax)) {
        GTEST_SKIP() << "The device has no AtomicVec2uMinMax (the visibility strategy's).";
    }
    const fs::path dir = test::makeTempDir("batch-pipeline-auto");
    std::vector<BatchInput> inputs;
    for (const std::uint32_t objects : {2u, 9u, 3u, 12u}) {
        const std::string name = "objects" + std::to_string(objects);
        test::writeGeneratedScene(dir / (name + ".glb"), objects, objects);
        inputs.push_back({dir / (name + ".glb"), name});
    }
    const auto run = [&](const std::string& folder, std::optional<render::StrategyChoice> strategy,
                         std::optional<std::uint64_t> line) {
        BatchOptions options = smallBatch(dir / folder);
        options.renderer.environment = test::testEnvironment();
        options.strategy = strategy;
        options.chooseStrategyPerModel = !strategy;
        options.visibilityFromTriangles = line;
        auto summary = runBatch(*context, inputs, options);
        EXPECT_TRUE(summary.ok()) << summary.error().message;
        if (summary.ok()) {
            EXPECT_EQ(summary->rendered, inputs.size()) << folder;
        }
        return test::batchOutputFiles(options.output);
    };
    const auto bundles =
        run("bundles", render::StrategyChoice::of(render::StrategyKind::Bundles, false), {});
    const auto visibility =
        run("visibility", render::StrategyChoice::of(render::StrategyKind::Visibility, false), {});
    const auto automatic = run("auto", std::nullopt, std::nullopt);
    std::map<std::string, std::uint64_t> triangles;
    for (const BatchInput& input : inputs) {
        EXPECT_EQ(metadataString(dir / "auto" / input.name, "strategy"), "\"bundles\"");
        EXPECT_EQ(metadataString(dir / "visibility" / input.name, "strategy"), "\"visibility\"");
        triangles[input.name] = std::stoull(metadataString(dir / "auto" / input.name, "triangles"));
    }
    EXPECT_EQ(automatic, bundles);  // On a CPU adapter, without a line.
    // The line at the third model's triangles: it and the larger one by visibility.
    const std::uint64_t line = triangles["objects9"];
    ASSERT_GT(line, triangles["objects3"]);
    ASSERT_GT(triangles["objects12"], line);
    const auto mixed = run("mixed", std::nullopt, line);
    ASSERT_EQ(mixed.size(), bundles.size());
    for (const auto& [name, bytes] : mixed) {
        const std::string model = name.substr(0, name.find('/'));
        const bool byVisibility = triangles[model] >= line;
        if (name.ends_with("metadata.json")) {
            EXPECT_EQ(metadataString(dir / "mixed" / model, "strategy"),
                      byVisibility ? "\"visibility\"" : "\"bundles\"");
            continue;
        }
        const auto& expected = byVisibility ? visibility : bundles;
        EXPECT_TRUE(expected.at(name) == bytes)
            << name << " differs from the " << (byVisibility ? "visibility" : "bundles")
            << " run's";
    }
    // The strategies' pictures differ: the comparison above tells them apart.
    const auto differs = [&](const auto& entry) {
        return entry.first.ends_with(".png") && bundles.at(entry.first) != entry.second;
    };
    EXPECT_TRUE(std::any_of(visibility.begin(), visibility.end(), differs));
    EXPECT_TRUE(context->checkNoErrors("automatic strategies").ok());
}

// A device whose storage bindings hold 64 KiB: a scene of 600 instances loads but cannot be
// uploaded with the bundles strategy (DeviceLimitsTest), so it fails at the "upload" stage.
TEST(BatchPipelineTest, ABadModelMidPipelineFailsAtItsStageWhileItsNeighboursRender) {
    gpu::ContextOptions contextOptions;
    contextOptions.limitOverrides = {256, 128 * 1024, 64 * 1024};
    auto context = gpu::Context::create(contextOptions);
    ASSERT_TRUE(context.ok()) << context.error().message;
    ASSERT_EQ(context->adapterDescription().backend, wgpu::BackendType::Vulkan);

    const fs::path dir = test::makeTempDir("batch-pipeline-bad");
    std::vector<BatchInput> inputs;
    for (const char* name : {"a", "b", "too-large", "c", "broken", "d"}) {
        const fs::path path = dir / "in" / (std::string(name) + ".glb");
        if (std::string(name) == "broken") {
            fs::create_directories(path.parent_path());
            std::ofstream(path) << "glTF, but not really";
        } else {
            test::writeGeneratedScene(path, std::string(name) == "too-large" ? 600 : 5,
                                      std::uint32_t(inputs.size() + 1));
        }
        inputs.push_back({path, name});
    }

    for (const std::size_t renderers : {2, 1}) {
        BatchOptions options = smallBatch(dir / ("renderers" + std::to_string(renderers)));
        options.renderer.environmentOptions = test::testEnvironmentOptions();
        options.renderers = renderers;
        auto summary = runBatch(*context, inputs, options);
        ASSERT_TRUE(summary.ok()) << summary.error().message;
        EXPECT_EQ(summary->rendered, 4u);
        EXPECT_EQ(summary->failed, 2u);
        std::map<std::string, std::string> stageOf;
        for (const Failure& failure : summary->failures) {
            stageOf[failure.file.stem().string()] = failure.stage;
        }
        EXPECT_EQ(stageOf["too-large"], "upload");
        EXPECT_EQ(stageOf["broken"], "load");
        EXPECT_EQ(stageOf.size(), 2u);
        const std::string log = test::readBytes(options.output / "failures.jsonl");
        EXPECT_NE(log.find("\"stage\":\"upload\""), std::string::npos) << log;
        EXPECT_NE(log.find("maxStorageBufferBindingSize"), std::string::npos) << log;
        for (const char* name : {"a", "b", "c", "d"}) {
            EXPECT_TRUE(fs::exists(options.output / name / "transforms.json")) << name;
            EXPECT_TRUE(fs::exists(options.output / name / "004.png")) << name;
        }
        EXPECT_FALSE(fs::exists(options.output / "too-large" / "transforms.json"));
    }
    EXPECT_TRUE(context->checkNoErrors("the batches").ok());
}

// BatchOptions::gpuTimestamps (encore batch -v) times every stage of the GPU's work and changes
// no file.
TEST(BatchPipelineTest, GpuTimestampsTimeEachStageAndChangeNoFile) {
    gpu::ContextOptions contextOptions;
    contextOptions.timestamps = true;
    auto context = gpu::Context::create(contextOptions);
    ASSERT_TRUE(context.ok()) << context.error().message;
    // Dawn's Null backend would time nothing real: the stage times below need a real adapter.
    ASSERT_EQ(context->adapterDescription().backend, wgpu::BackendType::Vulkan);
    if (!context->hasFeature(wgpu::FeatureName::TimestampQuery)) {
        GTEST_SKIP() << "The adapter has no timestamp queries.";
    }
    const fs::path dir = test::makeTempDir("batch-pipeline-timestamps");
    std::vector<BatchInput> inputs;
    for (std::uint32_t seed = 1; seed <= 3; ++seed) {
        const fs::path path = dir / "in" / ("m" + std::to_string(seed) + ".glb");
        test::writeGeneratedScene(path, 4, seed);
        inputs.push_back({path, "m" + std::to_string(seed)});
    }
    std::map<std::string, std::string> written[2];
    for (const bool timed : {false, true}) {
        BatchOptions options = smallBatch(dir / (timed ? "timed" : "untimed"));
        options.renderer.environmentOptions = test::testEnvironmentOptions();
        options.gpuTimestamps = timed;
        const auto start = std::chrono::steady_clock::now();
        auto summary = runBatch(*context, inputs, options);
        const double wallMilliseconds =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        ASSERT_TRUE(summary.ok()) << summary.error().message;
        EXPECT_EQ(summary->rendered, inputs.size());
        written[timed] = test::batchOutputFiles(options.output);
        if (!timed) {
            EXPECT_TRUE(summary->stages.gpuStages.empty());
            continue;
        }
        ASSERT_EQ(summary->stages.gpuStages.size(), render::kGpuStageCount);
        for (std::uint32_t stage = 0; stage < render::kGpuStageCount; ++stage) {
            const batch::GpuStageTime& time = summary->stages.gpuStages[stage];
            EXPECT_GT(time.timed, 0u) << render::kGpuStageNames[stage];
            EXPECT_EQ(time.untimed, 0u) << render::kGpuStageNames[stage];
            // Ticks converted to milliseconds: no stage of GPU work outlasts the whole batch.
            EXPECT_GT(time.milliseconds, 0.0) << render::kGpuStageNames[stage];
            EXPECT_LT(time.milliseconds, wallMilliseconds) << render::kGpuStageNames[stage];
        }
        // One pass per view (5 views: one target) and one tone mapping and copy per model.
        const auto& scene =
            summary->stages.gpuStages[render::gpuStageIndex(render::GpuStage::Scene)];
        EXPECT_EQ(scene.timed, inputs.size() * 5);
        // Fifteen multisampled views rasterised on the CPU take measurable time.
        EXPECT_GT(scene.milliseconds, 0.0);
    }
    EXPECT_TRUE(written[0] == written[1]);
    EXPECT_TRUE(context->checkNoErrors("the timed batches").ok());
}

// BatchOptions::renderers takes 1..kMaxRenderers, as `encore batch --renderers` does.
TEST(BatchPipelineTest, RendererCountsOutsideTheRangeAreRefused) {
    ENCORE_REQUIRE_VULKAN(context);
    const fs::path dir = test::makeTempDir("batch-pipeline-renderers");
    const fs::path path = dir / "in" / "m.glb";
    test::writeGeneratedScene(path, 2, 1);
    const std::vector<BatchInput> inputs{{path, "m"}};
    for (const std::size_t renderers : {std::size_t{0}, kMaxRenderers + 1}) {
        BatchOptions options = smallBatch(dir / "out");
        options.renderers = renderers;
        auto summary = runBatch(*context, inputs, options);
        ASSERT_FALSE(summary.ok()) << renderers;
        EXPECT_EQ(summary.error().code, ErrorCode::InvalidArgument);
    }
}

}  // namespace
}  // namespace encore::batch
