// A soak test: thousands of frames with instance, material, camera, tone mapping and texture
// updates, every strategy in turn and the scene reloaded (Renderer::prepare) at every switch.
// After a warm-up period, resident memory and the device's live buffers and textures (counted
// by Dawn's memory dump, gpu::ResourceStatistics) must not grow from one period to the next.
// Under AddressSanitizer (make test-sanitize) it runs fewer frames, checks object counts and
// leaks, but neither resident memory (ASan's quarantine holds freed memory by design) nor
// memory mappings (ASan's allocator maps regions of its own).

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <unistd.h>

#include <glm/gtc/matrix_transform.hpp>

#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "encore/gpu/ResourceStatistics.h"
#include "encore/render/Renderer.h"
#include "encore/scene/SceneGenerator.h"

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
// Growth allowed between the last two periods, at the same point of the same (strategy,
// scene): allocator noise, not a leak of a few kilobytes per frame.
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
    gpu::ResourceStatistics resources;
    std::uint64_t mappings = 0;
};

TEST(SoakTest, MemoryAndGpuObjectsStayFlatOverThousandsOfFrames) {
    // An own device: the counts are per device, and other tests' objects stay out of them.
    auto context = gpu::Context::create();
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
    const int cyclesPerPeriod = int(strategies.size());  // Scenes alternate: period 8 as well.
    std::vector<Sample> samples;
    const auto start = std::chrono::steady_clock::now();
    int frame = 0;
    for (int cycle = 0; cycle < cyclesPerPeriod * kPeriods; ++cycle) {
        const StrategyKind kind = strategies[cycle % strategies.size()];
        const scene::SceneData& scene = scenes[cycle % scenes.size()];
        auto prepared = renderer->prepare(scene, kind);
        ASSERT_TRUE(prepared.ok()) << prepared.error().message;
        const glm::vec3 center = (scene.bounds.min + scene.bounds.max) * 0.5f;
        const float radius = glm::length(scene.bounds.max - scene.bounds.min);
        for (int local = 0; local < kFramesPerCycle; ++local, ++frame) {
            const float t = float(frame) * 0.01f;
            for (std::size_t k = 0; k < 4; ++k) {
                const std::size_t instance = (std::size_t(frame) * 4 + k) % scene.instances.size();
                const glm::mat4 world = glm::rotate(scene.instances[instance].world, t,
                                                    glm::vec3(0.0f, 1.0f, 0.0f));
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
                renderer->setToneMapping({.exposure = 1.0f + 0.2f * std::sin(t)});
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
        samples.push_back({residentBytes(), gpu::resourceStatistics(context->device()),
                           gpu::processMemoryMappings()});
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_TRUE(context->checkNoErrors("the soak").ok());

    // Compare the last two periods sample by sample: same strategy, same scene, same point.
    std::int64_t worstGrowth = 0;
    for (int i = 0; i < cyclesPerPeriod; ++i) {
        const Sample& before = samples[cyclesPerPeriod * (kPeriods - 2) + i];
        const Sample& after = samples[cyclesPerPeriod * (kPeriods - 1) + i];
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
        worstGrowth = std::max(worstGrowth, after.resident - before.resident);
    }
    const Sample& warm = samples[cyclesPerPeriod - 1];
    const Sample& last = samples.back();
    std::printf(
        "soak: %d frames, %zu prepares in %.1f s (%.2f ms per frame, prepares included)\n"
        "soak: resident %.1f MiB after warm-up (%d frames), %.1f MiB at the end; worst growth "
        "between the last two periods %.2f MiB\n"
        "soak: live buffers %llu (%.2f MiB), textures %llu (%.2f MiB), memory mappings %llu "
        "at the end\n",
        frame, samples.size(), seconds, seconds * 1000.0 / frame,
        double(warm.resident) / 1048576.0, cyclesPerPeriod * kFramesPerCycle,
        double(last.resident) / 1048576.0, double(worstGrowth) / 1048576.0,
        (unsigned long long)last.resources.buffers, double(last.resources.bufferBytes) / 1048576.0,
        (unsigned long long)last.resources.textures,
        double(last.resources.textureBytes) / 1048576.0, (unsigned long long)last.mappings);
    for (int period = 0; period < kPeriods; ++period) {
        const Sample& end = samples[cyclesPerPeriod * (period + 1) - 1];
        std::printf("soak: period %d: resident %.2f MiB, %llu buffers, %llu textures, %llu mappings\n",
                    period, double(end.resident) / 1048576.0,
                    (unsigned long long)end.resources.buffers,
                    (unsigned long long)end.resources.textures, (unsigned long long)end.mappings);
    }
    if (!kSanitized) {
        EXPECT_LE(worstGrowth, kResidentGrowthLimit);
    }
}

}  // namespace
}  // namespace encore::render
