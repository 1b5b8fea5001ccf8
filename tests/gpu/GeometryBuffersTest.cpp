#include <gtest/gtest.h>

#include <set>
#include <vector>

#include "GpuTestSupport.h"
#include "encore/render/VertexBindings.h"
#include "encore/scene/SceneGenerator.h"

namespace encore::render {
namespace {

scene::SceneData generatedScene() {
    scene::GeneratorOptions options;
    options.objectCount = 16;
    options.meshCount = 8;
    options.textures = true;
    return test::generatedScene(options);
}

constexpr scene::Semantic kSemantics[] = {scene::Semantic::Position, scene::Semantic::Normal,
                                          scene::Semantic::Texcoord0};

// Every binding of every primitive: inside its buffer, 4-byte aligned, and reading exactly
// to the end of its bufferView, no further.
std::vector<PrimitiveBindings> bindAll(GeometryBuffers& geometry, const scene::SceneData& scene) {
    std::vector<PrimitiveBindings> all;
    for (const scene::Mesh& mesh : scene.meshes) {
        for (const scene::Primitive& primitive : mesh.primitives) {
            auto bindings = geometry.bind(primitive, kSemantics);
            EXPECT_TRUE(bindings.ok()) << bindings.error().message;
            for (const VertexBufferBinding& vertex : bindings->vertexBuffers) {
                EXPECT_EQ(vertex.offset % 4, 0u);
                EXPECT_LE(vertex.offset + vertex.size, vertex.buffer.GetSize());
            }
            const auto accessor = primitive.attribute(scene::Semantic::Position);
            const scene::Accessor& position = scene.accessors[accessor->index()];
            const scene::BufferView& view = scene.bufferViews[position.view.index()];
            // Slot 0 holds POSITION (location 0) at the accessor's offset in its view.
            EXPECT_EQ(bindings->vertexBuffers[0].size, view.byteLength - position.byteOffset);
            if (bindings->indices) {
                EXPECT_EQ(bindings->indices->offset % 2, 0u);
                EXPECT_LE(bindings->indices->offset + bindings->indices->size,
                          bindings->indices->buffer.GetSize());
                const scene::Accessor& indices = scene.accessors[primitive.indices->index()];
                EXPECT_GE(bindings->indices->size,
                          std::uint64_t(indices.count) * indices.elementSize());
            }
            all.push_back(std::move(*bindings));
        }
    }
    return all;
}

TEST(GeometryBuffersTest, AllViewsShareOneBuffer) {
    ENCORE_REQUIRE_VULKAN(context);
    const scene::SceneData scene = generatedScene();
    ASSERT_GE(scene.bufferViews.size(), 16u);  // Four views per mesh at least.
    GeometryBuffers geometry(context->device(), scene);
    const std::vector<PrimitiveBindings> all = bindAll(geometry, scene);
    ASSERT_EQ(all.size(), 8u);
    EXPECT_EQ(geometry.bufferCount(), 1u);
    std::set<std::uint64_t> offsets;
    for (const PrimitiveBindings& bindings : all) {
        EXPECT_EQ(bindings.vertexBuffers[0].buffer.Get(), all[0].vertexBuffers[0].buffer.Get());
        EXPECT_EQ(bindings.indices->buffer.Get(), all[0].vertexBuffers[0].buffer.Get());
        offsets.insert(bindings.vertexBuffers[0].offset);
    }
    EXPECT_EQ(offsets.size(), all.size());  // Each mesh its own positions.
    EXPECT_TRUE(context->checkNoErrors("geometry buffers").ok());
}

TEST(GeometryBuffersTest, SplitsPastTheBufferLimit) {
    ENCORE_REQUIRE_VULKAN(context);
    const scene::SceneData scene = generatedScene();
    std::uint64_t largestView = 0;
    for (const scene::BufferView& view : scene.bufferViews) {
        largestView = std::max<std::uint64_t>(largestView, view.byteLength);
    }
    // Room for about two views per buffer.
    GeometryBuffers geometry(context->device(), scene, 2 * largestView + 8);
    const std::vector<PrimitiveBindings> all = bindAll(geometry, scene);
    ASSERT_EQ(all.size(), 8u);
    EXPECT_GT(geometry.bufferCount(), 4u);
    std::set<WGPUBuffer> buffers;
    for (const PrimitiveBindings& bindings : all) {
        for (const VertexBufferBinding& vertex : bindings.vertexBuffers) {
            EXPECT_LE(vertex.buffer.GetSize(), 2 * largestView + 8);
            buffers.insert(vertex.buffer.Get());
        }
    }
    EXPECT_GT(buffers.size(), 1u);
    EXPECT_TRUE(context->checkNoErrors("geometry buffers, split").ok());
}

}  // namespace
}  // namespace encore::render
