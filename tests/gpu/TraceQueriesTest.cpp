// The GPU's traversal of a scene's hierarchies (trace_bvh.wgsl) against the CPU's
// (trace::closestHit), which RayCastTest checks against brute force.

#include <gtest/gtest.h>

#include <random>

#include "GpuTestSupport.h"
#include "scene/SceneGenerator.h"
#include "shaders/ShaderLibrary.h"
#include "trace/RayQueries.h"

namespace encore::trace {
namespace {

// Rays from around the scene's box towards points inside it.
std::vector<Ray> raysThrough(const scene::Bounds& bounds, std::uint32_t count, std::uint32_t seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const glm::vec3 size = glm::max(bounds.max - bounds.min, glm::vec3(1.0f));
    auto inside = [&](float margin) {
        return bounds.min - margin * size +
               (1.0f + 2.0f * margin) * size * glm::vec3(unit(random), unit(random), unit(random));
    };
    std::vector<Ray> rays(count);
    for (Ray& ray : rays) {
        ray.origin = inside(0.5f);
        ray.direction = inside(0.0f) - ray.origin;
    }
    return rays;
}

std::vector<GpuRayHit> traceOnGpu(gpu::Context& context,
                                  const TraceScene& scene,
                                  std::span<const Ray> rays) {
    shaders::ShaderLibrary shaders(context.device());
    auto queries = RayQueries::create(context.device(), shaders);
    EXPECT_TRUE(queries.ok()) << queries.error().message;
    const TraceSceneBuffers buffers =
        TraceSceneBuffers::upload(context.device(), queries->sceneLayout(), scene);
    auto hits = queries->closestHits(context, buffers, rays);
    EXPECT_TRUE(hits.ok()) << hits.error().message;
    EXPECT_TRUE(context.checkNoErrors("Tracing rays").ok());
    return hits.ok() ? *hits : std::vector<GpuRayHit>();
}

TEST(TraceQueriesTest, TheGpuFindsTheHitsTheCpuFinds) {
    ENCORE_REQUIRE_VULKAN(context);
    scene::GeneratorOptions options;
    options.objectCount = 100;
    options.meshCount = 6;
    options.tessellation = 6;
    options.layout = scene::SceneLayout::City;
    const scene::SceneData scene = test::generatedScene(options);
    auto builder = BvhBuilder::create();
    ASSERT_TRUE(builder.ok());
    auto trace = buildTraceScene(scene, *builder);
    ASSERT_TRUE(trace.ok()) << trace.error().message;

    const std::vector<Ray> rays = raysThrough(scene.bounds, 4096, 99);
    const std::vector<GpuRayHit> gpu = traceOnGpu(*context, *trace, rays);
    ASSERT_EQ(gpu.size(), rays.size());
    std::uint32_t hits = 0, disagreements = 0;
    for (std::size_t r = 0; r < rays.size(); ++r) {
        const std::optional<RayHit> cpu = closestHit(*trace, rays[r]);
        if (cpu.has_value() != gpu[r].hit()) {
            ++disagreements;  // A ray grazing an edge, rounded differently (fused multiplies).
            continue;
        }
        if (!cpu) {
            continue;
        }
        ++hits;
        EXPECT_NEAR(gpu[r].t, cpu->t, 1e-4f * std::max(1.0f, cpu->t)) << "ray " << r;
        if (gpu[r].object != cpu->object || gpu[r].triangle != cpu->triangle) {
            EXPECT_NEAR(gpu[r].t, cpu->t, 1e-5f * std::max(1.0f, cpu->t)) << "ray " << r;
        } else {
            EXPECT_NEAR(gpu[r].barycentric.x, cpu->barycentric.x, 1e-3f);
            EXPECT_NEAR(gpu[r].barycentric.y, cpu->barycentric.y, 1e-3f);
        }
    }
    EXPECT_GT(hits, rays.size() / 4);
    EXPECT_LE(disagreements, rays.size() / 500);
}

TEST(TraceQueriesTest, ASceneWithoutTrianglesHitsNothing) {
    ENCORE_REQUIRE_VULKAN(context);
    const TraceScene empty;
    scene::Bounds bounds;
    bounds.extend(glm::vec3(-1.0f));
    bounds.extend(glm::vec3(1.0f));
    const std::vector<Ray> rays = raysThrough(bounds, 256, 3);
    const std::vector<GpuRayHit> gpu = traceOnGpu(*context, empty, rays);
    ASSERT_EQ(gpu.size(), rays.size());
    for (const GpuRayHit& hit : gpu) {
        EXPECT_FALSE(hit.hit());
    }
}

// A ray that may not reach the surface misses it; one that may, hits it at the same distance.
TEST(TraceQueriesTest, TheRaysLimitsHold) {
    ENCORE_REQUIRE_VULKAN(context);
    scene::GeneratorOptions options;
    options.objectCount = 9;
    options.meshCount = 3;
    const scene::SceneData scene = test::generatedScene(options);
    auto builder = BvhBuilder::create();
    ASSERT_TRUE(builder.ok());
    auto trace = buildTraceScene(scene, *builder);
    ASSERT_TRUE(trace.ok());
    std::vector<Ray> rays = raysThrough(scene.bounds, 512, 17);
    const std::vector<GpuRayHit> unlimited = traceOnGpu(*context, *trace, rays);
    ASSERT_EQ(unlimited.size(), rays.size());
    std::vector<Ray> limited;
    std::vector<float> distances;
    for (std::size_t r = 0; r < rays.size(); ++r) {
        if (unlimited[r].hit()) {
            Ray shortRay = rays[r];
            shortRay.tMax = unlimited[r].t * 0.999f;
            limited.push_back(shortRay);
            distances.push_back(unlimited[r].t);
        }
    }
    ASSERT_GT(limited.size(), 50u);
    const std::vector<GpuRayHit> hits = traceOnGpu(*context, *trace, limited);
    ASSERT_EQ(hits.size(), limited.size());
    for (std::size_t r = 0; r < hits.size(); ++r) {
        EXPECT_FALSE(hits[r].hit()) << "ray " << r << " ends before its surface at " << distances[r]
                                    << " but hit at " << hits[r].t;
    }
}

}  // namespace
}  // namespace encore::trace
