#include <gtest/gtest.h>

#include <set>
#include <vector>

#include "GpuTestSupport.h"
#include "render/VertexBindings.h"
#include "scene/SceneGenerator.h"

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
std::vector<PrimitiveBindings> bindAll(const GeometryBuffers& geometry,
                                       const scene::SceneData& scene) {
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
    // Of the views primitives read (load-time mesh optimisation leaves the asset's own views in
    // place, unread, beside the new ones), each counted once.
    std::set<scene::BufferViewId> read;
    for (const scene::Mesh& mesh : scene.meshes) {
        for (const scene::Primitive& primitive : mesh.primitives) {
            for (const scene::VertexAttribute& attribute : primitive.attributes) {
                read.insert(scene.accessors[attribute.accessor.index()].view);
            }
            read.insert(scene.accessors[primitive.indices->index()].view);
        }
    }
    std::uint64_t largestView = 0;
    std::uint64_t totalBytes = 0;
    for (scene::BufferViewId id : read) {
        const std::uint64_t length = scene.bufferViews[id.index()].byteLength;
        largestView = std::max(largestView, length);
        totalBytes += length;
    }
    // Room for about two views per buffer.
    const std::uint64_t limit = 2 * largestView + 8;
    GeometryBuffers geometry(context->device(), scene, limit);
    const std::vector<PrimitiveBindings> all = bindAll(geometry, scene);
    ASSERT_EQ(all.size(), 8u);
    EXPECT_GE(geometry.bufferCount(), (totalBytes + limit - 1) / limit);
    std::set<WGPUBuffer> buffers;
    for (const PrimitiveBindings& bindings : all) {
        for (const VertexBufferBinding& vertex : bindings.vertexBuffers) {
            EXPECT_LE(vertex.buffer.GetSize(), limit);
            buffers.insert(vertex.buffer.Get());
        }
    }
    EXPECT_GT(buffers.size(), 1u);
    EXPECT_TRUE(context->checkNoErrors("geometry buffers, split").ok());
}

// The culling pass draws level k of a primitive from the index binding of level 0 with
// firstIndex = (level byteOffset - level 0 byteOffset) / index size (SceneData.h): the binding
// must reach the end of the view, past the last level, and the levels' views must be uploaded.
TEST(GeometryBuffersTest, IndexBindingsReachEveryLevelOfDetail) {
    ENCORE_REQUIRE_VULKAN(context);
    scene::GeneratorOptions options;
    options.objectCount = 8;
    options.meshCount = 8;
    options.tessellation = 24;
    const scene::SceneData scene = test::generatedScene(options);
    GeometryBuffers geometry(context->device(), scene);
    std::size_t levels = 0;
    for (const scene::Mesh& mesh : scene.meshes) {
        for (const scene::Primitive& primitive : mesh.primitives) {
            auto bindings = geometry.bind(primitive, kSemantics);
            ASSERT_TRUE(bindings.ok()) << bindings.error().message;
            ASSERT_TRUE(bindings->indices);
            const scene::Accessor& level0 = scene.accessors[primitive.indices->index()];
            const std::uint32_t size = level0.elementSize();
            for (const scene::LevelOfDetail& level : primitive.levels) {
                const scene::Accessor& indices = scene.accessors[level.indices.index()];
                ASSERT_EQ(indices.view, level0.view);
                const std::uint64_t firstIndex = (indices.byteOffset - level0.byteOffset) / size;
                EXPECT_LE((firstIndex + indices.count) * size, bindings->indices->size);
                ++levels;
            }
        }
    }
    EXPECT_GT(levels, 0u);
    EXPECT_TRUE(context->checkNoErrors("geometry buffers, levels of detail").ok());
}

}  // namespace
}  // namespace encore::render
