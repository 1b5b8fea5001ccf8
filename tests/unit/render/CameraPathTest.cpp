// Camera paths through the generated benchmark scenes (no GPU): reproducible, a smooth closed
// loop inside the scene that never enters an object, with most objects out of view.

#include "render/CameraPath.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "encore/scene/SceneData.h"
#include "render/culling/Frustum.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSamples = 2000;

scene::GeneratorOptions optionsFor(scene::SceneLayout layout, std::uint32_t objects) {
    scene::GeneratorOptions options;
    options.layout = layout;
    options.objectCount = objects;
    options.tessellation = 4;
    return options;
}

scene::SceneData load(const scene::GeneratorOptions& options) {
    auto glb = scene::generateSceneGlb(options);
    EXPECT_TRUE(glb.ok()) << glb.error().message;
    auto scene = scene::loadSceneFromMemory(*glb, {}, "generated");
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene.ok() ? std::move(*scene) : scene::SceneData{};
}

scene::Bounds meshBounds(const scene::SceneData& scene, const scene::Instance& instance) {
    scene::Bounds bounds;
    for (const auto& primitive : scene.meshes[instance.mesh.index()].primitives) {
        bounds.extend(primitive.bounds);
    }
    return bounds;
}

struct PathCase {
    scene::SceneLayout layout;
    std::uint32_t objects;
};

class CameraPathTest : public ::testing::TestWithParam<PathCase> {};

TEST_P(CameraPathTest, IsReproducibleClosedAndSmooth) {
    const auto options = optionsFor(GetParam().layout, GetParam().objects);
    const auto path = CameraPath::forLayout(options);
    const auto again = CameraPath::forLayout(options);
    ASSERT_TRUE(path && again);
    for (std::uint32_t frame = 0; frame < 10; ++frame) {
        EXPECT_EQ(path->camera(frame, 10, 16.0f / 9.0f).view,
                  again->camera(frame, 10, 16.0f / 9.0f).view);
    }
    EXPECT_LT(glm::distance(path->position(0.0f), path->position(1.0f)), 1e-3f);
    EXPECT_LT(glm::distance(path->position(0.25f), path->position(1.25f)), 1e-3f);
    const float step = path->length() / kSamples;
    for (std::uint32_t i = 0; i < kSamples; ++i) {
        const float t = float(i) / kSamples;
        const float next = float(i + 1) / kSamples;
        // Constant speed and a heading that turns gradually.
        EXPECT_NEAR(glm::distance(path->position(t), path->position(next)), step, 0.02f * step)
            << "at " << t;
        EXPECT_GT(glm::dot(path->direction(t), path->direction(next)), std::cos(glm::radians(8.0f)))
            << "at " << t;
        EXPECT_NEAR(glm::length(path->direction(t)), 1.0f, 1e-4f);
    }
    const Camera camera = path->camera(3, 10, 2.0f);
    EXPECT_EQ(camera.kind, ProjectionKind::Perspective);
    EXPECT_FLOAT_EQ(camera.nearPlane, CameraPath::kNearPlane);
    EXPECT_EQ(camera.position, path->position(0.3f));
    EXPECT_LT(glm::distance(path->cameraAtDistance(0.3f * path->length(), 2.0f).position,
                            camera.position),
              1e-3f);
}

// Every point of the path of a large scene lies inside its box; every point of any path lies
// outside every object, grown by the near plane so that no frame clips a neighbour (bounding
// spheres for the lattice's turned objects, boxes for the city's upright ones).
TEST_P(CameraPathTest, StaysInsideTheSceneAndOutsideEveryObject) {
    const auto options = optionsFor(GetParam().layout, GetParam().objects);
    const auto path = CameraPath::forLayout(options);
    ASSERT_TRUE(path);
    const scene::SceneData scene = load(options);
    const bool city = GetParam().layout == scene::SceneLayout::City;
    std::vector<Sphere> spheres;
    std::vector<scene::Bounds> boxes;
    for (const auto& instance : scene.instances) {
        const scene::Bounds local = meshBounds(scene, instance);
        spheres.push_back(worldSphere(local, instance.world));
        scene::Bounds box;
        for (int corner = 0; corner < 8; ++corner) {
            box.extend(glm::vec3(instance.world *
                                 glm::vec4((corner & 1) ? local.max.x : local.min.x,
                                           (corner & 2) ? local.max.y : local.min.y,
                                           (corner & 4) ? local.max.z : local.min.z, 1.0f)));
        }
        boxes.push_back(box);
    }
    const float margin = CameraPath::kNearPlane * 2.0f;
    // Small scenes are too small to hold their loop: it goes round them.
    const bool inside = GetParam().objects >= 1000;
    float nearest = INFINITY;
    for (std::uint32_t i = 0; i < kSamples; ++i) {
        const glm::vec3 p = path->position(float(i) / kSamples);
        ASSERT_TRUE(!inside || (glm::all(glm::greaterThan(p, scene.bounds.min)) &&
                                glm::all(glm::lessThan(p, scene.bounds.max))))
            << "sample " << i << " leaves the scene";
        for (std::size_t object = 0; object < scene.instances.size(); ++object) {
            if (city) {
                const glm::vec3 outside = glm::max(boxes[object].min - p, p - boxes[object].max);
                const float gap = std::max({outside.x, outside.y, outside.z});
                nearest = std::min(nearest, gap);
            } else {
                const Sphere& s = spheres[object];
                nearest = std::min(nearest, glm::distance(p, glm::vec3(s)) - s.w);
            }
        }
    }
    EXPECT_GT(nearest, margin) << "the path comes within " << nearest << " of an object";
}

// Looking along the path, most objects are behind or beside the camera: on average the
// frustum holds less than half of them (occlusion then hides most of those).
TEST_P(CameraPathTest, MostObjectsAreOutOfView) {
    if (GetParam().objects < 1000) {
        GTEST_SKIP() << "a loop round a small scene sees much of it";
    }
    const auto options = optionsFor(GetParam().layout, GetParam().objects);
    const auto path = CameraPath::forLayout(options);
    ASSERT_TRUE(path);
    const scene::SceneData scene = load(options);
    constexpr std::uint32_t kFrames = 24;
    double inView = 0.0;
    for (std::uint32_t frame = 0; frame < kFrames; ++frame) {
        const Camera camera = path->camera(frame, kFrames, 16.0f / 9.0f);
        const Frustum frustum = Frustum::fromViewProjection(camera.viewProjection());
        std::size_t visible = 0;
        for (const auto& instance : scene.instances) {
            visible += frustum.intersects(worldSphere(meshBounds(scene, instance), instance.world));
        }
        EXPECT_GT(visible, 0u) << "frame " << frame << " sees nothing";
        inView += double(visible) / double(scene.instances.size());
    }
    EXPECT_LT(inView / kFrames, 0.5);
}

INSTANTIATE_TEST_SUITE_P(GeneratedScenes,
                         CameraPathTest,
                         ::testing::Values(PathCase{scene::SceneLayout::Lattice, 2000},
                                           PathCase{scene::SceneLayout::Lattice, 30},
                                           PathCase{scene::SceneLayout::City, 2000},
                                           PathCase{scene::SceneLayout::City, 12}),
                         [](const auto& info) {
                             return std::string(scene::sceneLayoutName(info.param.layout)) +
                                    std::to_string(info.param.objects);
                         });

TEST(CameraPathTest, TheGridHasNoPath) {
    EXPECT_FALSE(CameraPath::forLayout(optionsFor(scene::SceneLayout::Grid, 100)));
}

}  // namespace
}  // namespace encore::render
