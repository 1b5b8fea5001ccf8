#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "scene/SceneGenerator.h"
#include "trace/RayCast.h"

namespace encore::trace {
namespace {

scene::SceneData generatedScene(std::uint32_t objects, scene::SceneLayout layout) {
    scene::GeneratorOptions options;
    options.objectCount = objects;
    options.meshCount = 6;
    options.layout = layout;
    options.tessellation = 6;
    auto glb = scene::generateSceneGlb(options);
    EXPECT_TRUE(glb.ok());
    auto loaded = scene::loadSceneFromMemory(*glb, {}, "generated.glb");
    EXPECT_TRUE(loaded.ok()) << loaded.error().message;
    return std::move(loaded).value();
}

struct WorldHit {
    float t = 0.0f;
    std::uint32_t instance = 0;
    std::uint32_t primitive = 0;
    std::uint32_t triangle = 0;
};

// Every triangle of every instance in world space, tested one by one.
std::optional<WorldHit> bruteForce(const scene::SceneData& scene, Ray ray) {
    std::optional<WorldHit> closest;
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const scene::Instance& instance = scene.instances[i];
        std::uint32_t primitiveIndex = 0;
        for (std::size_t m = 0; m < instance.mesh.index(); ++m) {
            primitiveIndex += std::uint32_t(scene.meshes[m].primitives.size());
        }
        for (const scene::Primitive& primitive : scene.meshes[instance.mesh.index()].primitives) {
            const std::vector<glm::vec4> positions =
                scene.readFloats(*primitive.attribute(scene::Semantic::Position));
            const std::vector<std::uint32_t> indices = scene.readIndices(*primitive.indices);
            for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
                TraceTriangle triangle;
                triangle.a =
                    glm::vec3(instance.world * glm::vec4(glm::vec3(positions[indices[t]]), 1));
                triangle.b =
                    glm::vec3(instance.world * glm::vec4(glm::vec3(positions[indices[t + 1]]), 1));
                triangle.c =
                    glm::vec3(instance.world * glm::vec4(glm::vec3(positions[indices[t + 2]]), 1));
                if (auto hit = intersectTriangle(ray, triangle)) {
                    ray.tMax = hit->t;
                    closest =
                        WorldHit{hit->t, std::uint32_t(i), primitiveIndex, std::uint32_t(t / 3)};
                }
            }
            ++primitiveIndex;
        }
    }
    return closest;
}

// Random rays from around the scene towards random points inside it: the hierarchies find the
// hit that testing every triangle finds.
void expectSameHitsAsBruteForce(const scene::SceneData& scene, std::uint32_t rays) {
    auto builder = BvhBuilder::create();
    ASSERT_TRUE(builder.ok());
    auto trace = buildTraceScene(scene, *builder);
    ASSERT_TRUE(trace.ok()) << trace.error().message;
    ASSERT_FALSE(trace->objects.empty());

    std::mt19937 random(1234);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const glm::vec3 size = scene.bounds.max - scene.bounds.min;
    auto inside = [&](float margin) {
        return scene.bounds.min - margin * size +
               (1.0f + 2.0f * margin) * size * glm::vec3(unit(random), unit(random), unit(random));
    };
    std::uint32_t hits = 0, disagreements = 0;
    for (std::uint32_t r = 0; r < rays; ++r) {
        const glm::vec3 origin = inside(0.5f);
        const Ray ray{origin, inside(0.0f) - origin};
        const std::optional<RayHit> found = closestHit(*trace, ray);
        const std::optional<WorldHit> expected = bruteForce(scene, ray);
        if (found.has_value() != expected.has_value()) {
            ++disagreements;  // A ray grazing an edge, rounded differently in the two spaces.
            continue;
        }
        if (!found) {
            continue;
        }
        ++hits;
        EXPECT_NEAR(found->t, expected->t, 1e-4f * std::max(1.0f, expected->t)) << "ray " << r;
        const TraceObject& object = trace->objects[found->object];
        const bool same = object.instance == expected->instance &&
                          object.primitive == expected->primitive &&
                          trace->triangles[found->triangle].index == expected->triangle;
        // Another triangle only where two are hit at the same distance (a shared edge).
        if (!same) {
            EXPECT_NEAR(found->t, expected->t, 1e-5f * std::max(1.0f, expected->t));
        }
    }
    EXPECT_GT(hits, rays / 4) << "the rays must mostly hit for the test to say much";
    EXPECT_LE(disagreements, rays / 500) << "hit/miss differs on more rays than grazing explains";
}

TEST(RayCastTest, GridSceneHitsAsBruteForce) {
    expectSameHitsAsBruteForce(generatedScene(64, scene::SceneLayout::Grid), 1500);
}

TEST(RayCastTest, CitySceneHitsAsBruteForce) {
    expectSameHitsAsBruteForce(generatedScene(48, scene::SceneLayout::City), 1500);
}

TEST(RayCastTest, ARayIntoEmptySpaceMissesAndTheFarthestLimitHolds) {
    const scene::SceneData scene = generatedScene(8, scene::SceneLayout::Grid);
    auto builder = BvhBuilder::create();
    ASSERT_TRUE(builder.ok());
    auto trace = buildTraceScene(scene, *builder);
    ASSERT_TRUE(trace.ok());
    // Above the middle of the first instance's first triangle.
    const scene::Primitive& primitive = scene.meshes[scene.instances[0].mesh.index()].primitives[0];
    const std::vector<glm::vec4> positions =
        scene.readFloats(*primitive.attribute(scene::Semantic::Position));
    const std::vector<std::uint32_t> indices = scene.readIndices(*primitive.indices);
    const glm::vec3 middle = glm::vec3(
        scene.instances[0].world *
        glm::vec4(
            glm::vec3(positions[indices[0]] + positions[indices[1]] + positions[indices[2]]) / 3.0f,
            1.0f));
    const glm::vec3 above = glm::vec3(middle.x, scene.bounds.max.y + 10.0f, middle.z);
    // Straight up from above everything: nothing.
    EXPECT_FALSE(closestHit(*trace, Ray{above, {0.0f, 1.0f, 0.0f}}).has_value());
    // Down onto that triangle (or what covers it): a hit, unless the ray may not go that far.
    const auto hit = closestHit(*trace, Ray{above, {0.0f, -1.0f, 0.0f}});
    ASSERT_TRUE(hit.has_value());
    EXPECT_GT(hit->t, 10.0f);
    EXPECT_FALSE(closestHit(*trace, Ray{above, {0.0f, -1.0f, 0.0f}, 0.0f, hit->t * 0.99f}));
}

}  // namespace
}  // namespace encore::trace
