// The generator's layouts (scene::SceneLayout): every layout loads as valid glTF with one
// instance per object, the same seed gives the same bytes, and the lattice and the city stand
// where their public layouts say.

#include <gtest/gtest.h>

#include <algorithm>

#include "encore/scene/SceneData.h"
#include "scene/SceneGenerator.h"

namespace encore::scene {
namespace {

GeneratorOptions optionsFor(SceneLayout layout, std::uint32_t objects) {
    GeneratorOptions options;
    options.layout = layout;
    options.objectCount = objects;
    options.tessellation = 4;
    return options;
}

SceneData load(const GeneratorOptions& options) {
    auto glb = generateSceneGlb(options);
    EXPECT_TRUE(glb.ok()) << glb.error().message;
    auto scene = loadSceneFromMemory(*glb, {}, std::string(sceneLayoutName(options.layout)));
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene.ok() ? std::move(*scene) : SceneData{};
}

class SceneLayoutTest : public ::testing::TestWithParam<SceneLayout> {};

TEST_P(SceneLayoutTest, LoadsWithOneInstancePerObjectAndIsDeterministic) {
    for (std::uint32_t objects : {1u, 13u, 200u, 1001u}) {
        SCOPED_TRACE(objects);
        const GeneratorOptions options = optionsFor(GetParam(), objects);
        const SceneData scene = load(options);
        EXPECT_EQ(scene.instances.size(), objects);
        EXPECT_FALSE(scene.bounds.empty());
        EXPECT_EQ(*generateSceneGlb(options), *generateSceneGlb(options));
    }
    GeneratorOptions other = optionsFor(GetParam(), 200);
    other.seed = 2;
    EXPECT_NE(*generateSceneGlb(other), *generateSceneGlb(optionsFor(GetParam(), 200)));
}

INSTANTIATE_TEST_SUITE_P(AllLayouts,
                         SceneLayoutTest,
                         ::testing::Values(SceneLayout::Grid,
                                           SceneLayout::Lattice,
                                           SceneLayout::City),
                         [](const auto& info) { return std::string(sceneLayoutName(info.param)); });

TEST(SceneLayoutTest, LatticeIsWideAndFlatAndItsPointsAreWhereTheLayoutSays) {
    const GeneratorOptions options = optionsFor(SceneLayout::Lattice, 10'000);
    const LatticeLayout lattice = latticeLayout(options);
    EXPECT_GE(lattice.side * lattice.side * lattice.layers, options.objectCount);
    EXPECT_GT(lattice.layers, 1u);
    EXPECT_GE(lattice.side, 3 * lattice.layers) << "flat-ish: wider than high";
    const SceneData scene = load(options);
    for (std::uint32_t i : {0u, 1u, lattice.side, lattice.side * lattice.side, 9'999u}) {
        const glm::vec3 expected =
            lattice.origin + lattice.spacing * glm::vec3(float(i % lattice.side),
                                                         float(i / (lattice.side * lattice.side)),
                                                         float((i / lattice.side) % lattice.side));
        const glm::vec3 translation(scene.instances[i].world[3]);
        EXPECT_NEAR(glm::distance(translation, expected), 0.0f, 1e-4f) << "object " << i;
    }
}

// Buildings stand on the ground inside their blocks; nothing stands on a street's centre line.
TEST(SceneLayoutTest, CityBuildingsStandInTheirBlocksAndLeaveTheStreetsFree) {
    const GeneratorOptions options = optionsFor(SceneLayout::City, 1200);
    const CityLayout city = cityLayout(options);
    EXPECT_EQ(city.blocksPerSide, 10u);  // 100 blocks of 12 objects.
    const SceneData scene = load(options);
    ASSERT_EQ(scene.instances.size(), 1200u);
    std::uint32_t buildings = 0;
    float tallest = 0.0f;
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& instance = scene.instances[i];
        Bounds box;
        for (const Primitive& primitive : scene.meshes[instance.mesh.index()].primitives) {
            for (int corner = 0; corner < 8; ++corner) {
                const glm::vec3 local(
                    (corner & 1) ? primitive.bounds.max.x : primitive.bounds.min.x,
                    (corner & 2) ? primitive.bounds.max.y : primitive.bounds.min.y,
                    (corner & 4) ? primitive.bounds.max.z : primitive.bounds.min.z);
                box.extend(glm::vec3(instance.world * glm::vec4(local, 1.0f)));
            }
        }
        EXPECT_NEAR(box.min.y, 0.0f, 0.05f) << "object " << i << " should stand on the ground";
        const bool building = i % CityLayout::kObjectsPerBlock < 9;
        if (building) {
            ++buildings;
            tallest = std::max(tallest, box.max.y);
            EXPECT_GE(box.max.y, 1.5f - 1e-3f);
            EXPECT_LE(box.max.y, city.maxBuildingHeight + 1e-3f);
        }
        // Clear of every street's centre line (and a camera's near plane) in X and in Z.
        for (std::uint32_t k = 0; k <= city.blocksPerSide; ++k) {
            const float street = city.streetCenter(int(k));
            for (int axis : {0, 2}) {
                const bool crosses = box.min[axis] < street + 0.4f && box.max[axis] > street - 0.4f;
                EXPECT_FALSE(crosses)
                    << "object " << i << " reaches street " << k << " (axis " << axis << ")";
            }
        }
    }
    EXPECT_EQ(buildings, 900u);
    EXPECT_GT(tallest, 5.0f) << "a few towers among the low buildings";
}

}  // namespace
}  // namespace encore::scene
