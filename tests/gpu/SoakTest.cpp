// A soak test: thousands of frames with instance, material, camera, tone mapping and texture
// updates, every strategy in turn and the scene reloaded (Renderer::prepare) at every switch.
// After a warm-up period, the heap bytes in use, resident memory, memory mappings and the
// device's live buffers and textures (counted by Dawn's memory dump, gpu::ResourceStatistics)
// must not grow from one period to the next. Under AddressSanitizer (make test-sanitize) it runs
// fewer frames, checks object counts and leaks, but not memory (ASan's quarantine holds freed
// memory by design, and its allocator maps regions of its own).

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <malloc.h>
#include <unistd.h>

#include <glm/gtc/matrix_transform.hpp>

#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "encore/render/Renderer.h"
#include "gpu/ResourceStatistics.h"
#include "scene/SceneGenerator.h"

namespace encore::render {
namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitized = true;
constexpr int kFramesPerCycle = 40;
#else
constexpr bool kSanitized = false;
constexpr int kFramesPerCycle = 300;
#endif
constexpr std::uint32_t kSize = 64;
constexpr int kPeriods = 4;  // The first is warm-up.
// A leak of a kilobyte per frame adds 2.4 MB per period (2,400 frames) to the bytes malloc has
// handed out and not got back, at every point of every period. Memory that is not leaked also
// steps up once in a while on a busy two-core machine: lavapipe's threads allocate lazily (1.1 MB
// of heap once), glibc keeps freed pages (after one large free it raises its mmap threshold and
// serves the next large blocks from the heap: one-off resident steps of 7.5 MiB). So each check
// takes the median over a period's points and the least growing of the last two periods.
constexpr std::int64_t kHeapGrowthLimit = 1024 * 1024;
constexpr std::int64_t kResidentGrowthLimit = 4 * 1024 * 1024;
// lavapipe maps every buffer and descriptor set: a leak of either per frame would add thousands.
constexpr std::uint64_t kMappingGrowthLimit = 64;

std::int64_t residentBytes() {
    long pages = 0;
    long resident = 0;
    if (std::FILE* statm = std::fopen("/proc/self/statm", "r")) {
        if (std::fscanf(statm, "%ld %ld", &pages, &resident) != 2) {
            resident = 0;
        }
        std::fclose(statm);
    }
    return std::int64_t(resident) * ::sysconf(_SC_PAGESIZE);
}

// Bytes malloc has handed out and not got back, on every thread's arena and in mmapped blocks.
std::int64_t heapBytesInUse() {
    const struct mallinfo2 info = ::mallinfo2();
    return std::int64_t(info.uordblks + info.hblkhd);
}

template <typename Value>
Value median(std::vector<Value> values) {
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    return values[values.size() / 2];
}

scene::SceneData generatedScene(std::uint32_t objects, std::uint32_t seed) {
    scene::GeneratorOptions generator;
    generator.objectCount = objects;
    generator.meshCount = 4;
    generator.materialCount = 3;
    generator.seed = seed;
    auto glb = scene::generateSceneGlb(generator);
    EXPECT_TRUE(glb.ok());
    auto loaded = scene::loadSceneFromMemory(*glb, {}, "soak-" + std::to_string(seed) + ".glb");
    EXPECT_TRUE(loaded.ok());
    return std::move(*loaded);
}

struct Sample {
    std::int64_t resident = 0;
    std::int64_t heapInUse = 0;
    gpu::ResourceStatistics resources;
    std::uint64_t mappings = 0;
};

TEST(SoakTest, MemoryAndGpuObjectsStayFlatOverThousandsOfFrames) {
    // An own device: the counts are per device, and other tests' objects stay out of them.
    gpu::ContextOptions contextOptions;
    render::requestVisibilityFeatures(contextOptions);
    auto context = gpu::Context::create(contextOptions);
    ASSERT_TRUE(context.ok()) << context.error().message;
    ASSERT_EQ(context->adapterDescription().backend, wgpu::BackendType::Vulkan);

    const std::vector<scene::SceneData> scenes = {generatedScene(48, 1), generatedScene(30, 2)};
    RendererOptions options = test::pixelTestOptions(kSize, kSize, 1, DebugChannel::Shaded);
    options.environment = nullptr;  // The shared test environment lives on another device.
    options.environmentOptions = test::testEnvironmentOptions();
    auto renderer = Renderer::create(*context, options);
    ASSERT_TRUE(renderer.ok()) << renderer.error().message;

    scene::Image replacement;
    replacement.name = "soak replacement";
    replacement.width = replacement.height = 4;
    const auto strategies = allStrategies();
    // Scenes alternate within a period, so that each period repeats the same cycles.
    const int cyclesPerPeriod = int(strategies.size());
    std::vector<Sample> samples;
    const auto start = std::chrono::steady_clock::now();
    int frame = 0;
    for (int cycle = 0; cycle < cyclesPerPeriod * kPeriods; ++cycle) {
        const StrategyKind kind = strategies[cycle % strategies.size()];
        const scene::SceneData& scene = scenes[(cycle % cyclesPerPeriod) % scenes.size()];
        auto prepared = renderer->prepare(scene, kind);
        ASSERT_TRUE(prepared.ok()) << prepared.error().message;
        const glm::vec3 center = (scene.bounds.min + scene.bounds.max) * 0.5f;
        const float radius = glm::length(scene.bounds.max - scene.bounds.min);
        for (int local = 0; local < kFramesPerCycle; ++local, ++frame) {
            const float t = float(frame) * 0.01f;
            for (std::size_t k = 0; k < 4; ++k) {
                const std::size_t instance = (std::size_t(frame) * 4 + k) % scene.instances.size();
                const glm::mat4 world =
                    glm::rotate(scene.instances[instance].world, t, glm::vec3(0.0f, 1.0f, 0.0f));
                ASSERT_TRUE(renderer->updateInstance(instance, world).ok());
            }
            if (frame % 4 == 0) {
                const scene::MaterialId material{std::uint32_t(frame % scene.materials.size())};
                scene::Material value = scene.materials[material.index()];
                value.baseColorFactor = glm::vec4(0.5f + 0.5f * std::sin(t), 0.4f, 0.6f, 1.0f);
                value.roughnessFactor = 0.5f + 0.4f * std::cos(t);
                ASSERT_TRUE(renderer->updateMaterial(material, value).ok());
            }
            if (frame % 10 == 0) {
                ASSERT_TRUE(renderer->setToneMapping({.exposure = 1.0f + 0.2f * std::sin(t)}).ok());
            }
            if (local == kFramesPerCycle / 2) {
                // Strategies with materials replace a texture (a new texture, bind group and
                // re-recorded bundles); the others have none to replace.
                replacement.rgba8.assign(4 * 4 * 4, std::uint8_t(frame));
                auto replaced = renderer->replaceBaseColorImage(scene::MaterialId{0u}, replacement);
                if (!replaced) {
                    ASSERT_EQ(replaced.error().code, ErrorCode::Unsupported)
                        << replaced.error().message;
                }
            }
            const glm::vec3 eye = center + radius * glm::vec3(std::cos(t), 0.4f, std::sin(t));
            renderer->renderFrame(Camera::lookAt(eye, center, 0.8f, 1.0f, 0.01f, 4.0f * radius));
            if (frame % 50 == 49) {
                context->waitForIdle();  // Keep the queue from running ahead of lavapipe.
            }
        }
        // Every cycle ends on a real image: something was drawn over the background.
        auto image = renderer->readImage();
        ASSERT_TRUE(image.ok()) << image.error().message;
        const test::Rgba corner = test::pixelAt(*image, 0, 0);
        EXPECT_GT(test::coveredFraction(*image, corner), 0.01)
            << strategyName(kind) << " drew nothing in cycle " << cycle;
        context->waitForIdle();
        context->device().Tick();
        samples.push_back({residentBytes(), heapBytesInUse(),
                           gpu::resourceStatistics(context->device()),
                           gpu::processMemoryMappings()});
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_TRUE(context->checkNoErrors("the soak").ok());

    // Compare periods sample by sample: same strategy, same scene, same point of the cycle.
    const auto at = [&](int period, int i) -> const Sample& {
        return samples[std::size_t(cyclesPerPeriod * period + i)];
    };
    std::vector<std::int64_t> heapGrowths[kPeriods];
    std::vector<std::int64_t> residentGrowths[kPeriods];
    for (int i = 0; i < cyclesPerPeriod; ++i) {
        const Sample& before = at(kPeriods - 2, i);
        const Sample& after = at(kPeriods - 1, i);
        const std::string where = "cycle " + std::to_string(i) + " of the period (" +
                                  std::string(strategyName(strategies[i])) + ")";
        EXPECT_EQ(after.resources.buffers, before.resources.buffers) << where;
        EXPECT_EQ(after.resources.textures, before.resources.textures) << where;
        EXPECT_EQ(after.resources.bufferBytes, before.resources.bufferBytes) << where;
        EXPECT_EQ(after.resources.textureBytes, before.resources.textureBytes) << where;
        // Mappings also come from malloc arenas and thread stacks, and ASan's allocator maps
        // its own regions: a loose bound, and only without it.
        if (!kSanitized) {
            EXPECT_LE(after.mappings, before.mappings + kMappingGrowthLimit) << where;
        }
        for (int period = 2; period < kPeriods; ++period) {
            heapGrowths[period].push_back(at(period, i).heapInUse - at(period - 1, i).heapInUse);
            residentGrowths[period].push_back(at(period, i).resident - at(period - 1, i).resident);
        }
    }
    // The median over the period's points: a leak moves all of them, a busy moment one.
    std::int64_t heapGrowth = std::numeric_limits<std::int64_t>::max();
    std::int64_t residentGrowth = std::numeric_limits<std::int64_t>::max();
    for (int period = 2; period < kPeriods; ++period) {
        heapGrowth = std::min(heapGrowth, median(heapGrowths[period]));
        residentGrowth = std::min(residentGrowth, median(residentGrowths[period]));
    }
    const Sample& warm = samples[cyclesPerPeriod - 1];
    const Sample& last = samples.back();
    std::printf(
        "soak: %d frames, %zu prepares in %.1f s (%.2f ms per frame, prepares included)\n"
        "soak: resident %.1f MiB after warm-up (%d frames), %.1f MiB at the end; growth at the "
        "same point (median, least growing period): heap in use %.3f MiB, resident %.2f MiB\n"
        "soak: live buffers %llu (%.2f MiB), textures %llu (%.2f MiB), memory mappings %llu "
        "at the end\n",
        frame, samples.size(), seconds, seconds * 1000.0 / frame, double(warm.resident) / 1048576.0,
        cyclesPerPeriod * kFramesPerCycle, double(last.resident) / 1048576.0,
        double(heapGrowth) / 1048576.0, double(residentGrowth) / 1048576.0,
        (unsigned long long)last.resources.buffers, double(last.resources.bufferBytes) / 1048576.0,
        (unsigned long long)last.resources.textures,
        double(last.resources.textureBytes) / 1048576.0, (unsigned long long)last.mappings);
    for (int period = 0; period < kPeriods; ++period) {
        const Sample& end = samples[cyclesPerPeriod * (period + 1) - 1];
        std::printf(
            "soak: period %d: resident %.2f MiB, heap in use %.2f MiB, %llu buffers, "
            "%llu textures, %llu mappings\n",
            period, double(end.resident) / 1048576.0, double(end.heapInUse) / 1048576.0,
            (unsigned long long)end.resources.buffers, (unsigned long long)end.resources.textures,
            (unsigned long long)end.mappings);
    }
    // ASan's allocator has no mallinfo and holds freed memory in quarantine by design.
    if (!kSanitized) {
        EXPECT_LE(heapGrowth, kHeapGrowthLimit);
        EXPECT_LE(residentGrowth, kResidentGrowthLimit);
    }
}

}  // namespace
}  // namespace encore::render
