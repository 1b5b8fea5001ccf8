// Issue 32: a primitive whose index accessor has count 0 in an empty buffer (a triangle fan of
// two indices, as a fuzzed file gave) is uploaded and drawn without copying from the buffer's
// null data(): GeometryBuffers copied it with memcpy (UBSan: null pointer passed as argument
// 2). The sanitizer build (make test-sanitize) runs these.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "GltfBuilder.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "encore/render/Renderer.h"
#include "render/VertexBindings.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSize = 32;

scene::SceneData fanWithoutTriangles() {
    auto scene = scene::loadSceneFromMemory(test::fanWithoutTriangles().toGlb(), {}, "fan.glb");
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene.ok() ? std::move(*scene) : scene::SceneData{};
}

TEST(EmptyBytesTest, GeometryBuffersUploadAnEmptyIndexView) {
    ENCORE_REQUIRE_VULKAN(context);
    const scene::SceneData scene = fanWithoutTriangles();
    ASSERT_EQ(scene.meshes.size(), 1u);
    const scene::Primitive& primitive = scene.meshes[0].primitives.at(0);
    ASSERT_TRUE(primitive.indices);
    const scene::Accessor& indices = scene.accessors[primitive.indices->index()];
    ASSERT_EQ(indices.count, 0u);
    ASSERT_TRUE(
        scene.buffers[scene.bufferViews[indices.view.index()].buffer.index()].bytes.empty());

    GeometryBuffers geometry(context->device(), scene);
    constexpr scene::Semantic kSemantics[] = {scene::Semantic::Position, scene::Semantic::Normal};
    auto bindings = geometry.bind(primitive, kSemantics);
    ASSERT_TRUE(bindings.ok()) << bindings.error().message;
    EXPECT_TRUE(context->checkNoErrors("geometry buffers of an empty index view").ok());
}

class EmptyBytesRenderTest : public ::testing::TestWithParam<StrategyKind> {};

TEST_P(EmptyBytesRenderTest, FanWithoutTrianglesDrawsNothing) {
    ENCORE_REQUIRE_VULKAN(context);
    const scene::SceneData scene = fanWithoutTriangles();
    auto renderer = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
    ASSERT_TRUE(renderer.ok()) << renderer.error().message;
    auto prepared = renderer->prepare(scene, GetParam());
    ASSERT_TRUE(prepared.ok()) << prepared.error().message;
    const Camera camera = Camera::framing(scene.bounds, 1.0f, 0.0f, 0.8f);
    renderer->renderFrame(camera);
    auto image = renderer->readImage();
    ASSERT_TRUE(image.ok()) << image.error().message;
    EXPECT_TRUE(context->checkNoErrors("rendering a fan without triangles").ok());
    const test::Rgba background = test::pixelAt(*image, 0, 0);
    for (std::uint32_t y = 0; y < kSize; ++y) {
        for (std::uint32_t x = 0; x < kSize; ++x) {
            ASSERT_EQ(test::channelDistance(test::pixelAt(*image, x, y), background), 0)
                << "pixel (" << x << ", " << y << ") differs from the background";
        }
    }
}

INSTANTIATE_TEST_SUITE_P(AllStrategies,
                         EmptyBytesRenderTest,
                         ::testing::ValuesIn(allStrategies()),
                         [](const auto& info) { return test::strategyTestName(info.param); });

}  // namespace
}  // namespace encore::render
