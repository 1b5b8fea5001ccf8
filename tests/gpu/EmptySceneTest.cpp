// Scenes that draw nothing (no nodes, nodes without meshes, meshes whose every primitive was
// skipped or that have none) render the background alone with every strategy: no validation
// errors from zero-sized buffers, zero draws or zero instances.

#include <gtest/gtest.h>

#include <algorithm>

#include "GltfBuilder.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "encore/render/Renderer.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSize = 32;

struct EmptyCase {
    std::string name;
    test::GltfBuilder (*build)();
};

test::GltfBuilder sceneWithoutNodes() {
    test::GltfBuilder builder;
    builder.json()["scenes"] = nlohmann::json::array({nlohmann::json::object()});
    builder.json()["scene"] = 0;
    return builder;
}

test::GltfBuilder nodesWithoutMeshes() {
    test::GltfBuilder builder;
    const auto child = builder.addNode({});
    builder.addScene({builder.addNode({.children = {child}})});
    return builder;
}

test::GltfBuilder meshWithoutPrimitives() {
    test::GltfBuilder builder;
    builder.json()["meshes"] = nlohmann::json::array({{{"primitives", nlohmann::json::array()}}});
    builder.addScene({builder.addNode({.mesh = 0}), builder.addNode({.mesh = 0})});
    return builder;
}

test::GltfBuilder primitivesWithoutPosition() {
    test::GltfBuilder builder;
    const auto normals = builder.addNormals({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    const auto mesh = builder.addMesh({.attributes = {{"NORMAL", normals}}});
    builder.addScene({builder.addNode({.mesh = mesh})});
    return builder;
}

test::GltfBuilder nothingAtAll() {
    return test::GltfBuilder();
}

const std::vector<EmptyCase>& emptyCases() {
    static const std::vector<EmptyCase> cases = {
        {"SceneWithoutNodes", sceneWithoutNodes},
        {"NodesWithoutMeshes", nodesWithoutMeshes},
        {"MeshWithoutPrimitives", meshWithoutPrimitives},
        {"PrimitivesWithoutPosition", primitivesWithoutPosition},
        {"NothingAtAll", nothingAtAll},
    };
    return cases;
}

class EmptySceneTest : public ::testing::TestWithParam<std::tuple<StrategyKind, std::size_t>> {};

TEST_P(EmptySceneTest, RendersTheBackgroundOnly) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto [kind, caseIndex] = GetParam();
    const EmptyCase& empty = emptyCases()[caseIndex];
    auto scene = scene::loadSceneFromMemory(empty.build().toGlb(), {}, "empty.glb");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_FALSE(scene->warnings.empty());
    auto renderer = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
    ASSERT_TRUE(renderer.ok()) << renderer.error().message;
    auto prepared = renderer->prepare(*scene, kind);
    ASSERT_TRUE(prepared.ok()) << prepared.error().message;
    // Automatic framing of empty bounds, as `encore render` does.
    const Camera camera = Camera::framing(scene->bounds, 1.0f, 0.0f, 0.8f);
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            ASSERT_TRUE(std::isfinite(camera.view[c][r]) && std::isfinite(camera.projection[c][r]));
        }
    }
    renderer->renderFrame(camera);
    renderer->renderFrame(camera);  // A second frame reuses what the first prepared.
    auto image = renderer->readImage();
    ASSERT_TRUE(image.ok()) << image.error().message;
    EXPECT_TRUE(context->checkNoErrors("rendering an empty scene").ok());
    ASSERT_EQ(image->width, kSize);
    const test::Rgba background = test::pixelAt(*image, 0, 0);
    for (std::uint32_t y = 0; y < kSize; ++y) {
        for (std::uint32_t x = 0; x < kSize; ++x) {
            ASSERT_EQ(test::channelDistance(test::pixelAt(*image, x, y), background), 0)
                << "pixel (" << x << ", " << y << ") differs from the background";
        }
    }
}

INSTANTIATE_TEST_SUITE_P(AllStrategies,
                         EmptySceneTest,
                         ::testing::Combine(::testing::ValuesIn(allStrategies()),
                                            ::testing::Range<std::size_t>(0, emptyCases().size())),
                         [](const auto& info) {
                             return test::strategyTestName(std::get<0>(info.param)) + "_" +
                                    emptyCases()[std::get<1>(info.param)].name;
                         });

}  // namespace
}  // namespace encore::render
