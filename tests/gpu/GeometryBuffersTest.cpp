#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <memory>
#include <set>
#include <thread>
#include <vector>

#include "GpuTestSupport.h"
#include "gpu/Readback.h"
#include "gpu/StagingBuffers.h"
#include "render/SharedGeometryLayout.h"
#include "render/StagedGeometry.h"
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

namespace encore::render {
namespace {

// The shared buffers' bytes, read back.
std::vector<std::vector<std::uint8_t>> sharedBytes(gpu::Context& context,
                                                   const GeometryBuffers& geometry) {
    std::vector<std::vector<std::uint8_t>> all;
    for (const wgpu::Buffer& buffer : geometry.sharedBuffers()) {
        auto bytes = gpu::readBuffer(context, buffer, 0, buffer.GetSize());
        EXPECT_TRUE(bytes.ok());
        all.push_back(bytes.ok() ? std::move(*bytes) : std::vector<std::uint8_t>{});
    }
    return all;
}

// Geometry that other threads copied into staging buffers, in pieces that cross views, gaps and
// buffers, uploads the same bytes as geometry mapped at creation; pieces no thread started are
// copied by the uploading thread, and those still queued when the staging goes away do nothing.
TEST(StagedGeometryTest, StagedBuffersHoldWhatMappedOnesHold) {
    ENCORE_REQUIRE_VULKAN(context);
    const scene::SceneData scene = generatedScene();
    std::uint64_t largestView = 0;
    const SharedGeometryLayout whole = sharedGeometryLayout(scene, ~std::uint64_t(0));
    ASSERT_EQ(whole.buffers.size(), 1u);
    for (const auto& view : whole.buffers[0].views) {
        largestView = std::max(largestView, view.length);
    }
    const std::uint64_t limit = 2 * largestView + 8;  // Several shared buffers.
    const SharedGeometryLayout layout = sharedGeometryLayout(scene, limit);
    ASSERT_GT(layout.buffers.size(), 2u);
    bool gap = false;  // Between views, or at a buffer's end: zeros in both uploads.
    for (const SharedGeometryLayout::Buffer& buffer : layout.buffers) {
        std::uint64_t end = 0;
        for (const SharedGeometryLayout::View& view : buffer.views) {
            gap = gap || view.offset > end;
            end = view.offset + view.length;
        }
        gap = gap || buffer.size % 4 != 0;
    }
    EXPECT_TRUE(gap);
    const GeometryBuffers mapped(context->device(), scene, limit);
    const auto expected = sharedBytes(*context, mapped);

    // Staging buffers that hold other bytes, as reused ones do: the gaps must be zeroed.
    auto staging = std::make_shared<gpu::StagingBuffers>(*context);
    std::vector<wgpu::Buffer> dirty;
    for (std::size_t i = 0; i < layout.buffers.size(); ++i) {
        dirty.push_back(staging->acquire(1));
        std::memset(dirty.back().GetMappedRange(), 0xAB, dirty.back().GetSize());
    }
    for (wgpu::Buffer& buffer : dirty) {
        staging->giveBack(std::move(buffer), true);
    }
    for (int round = 0; round < 2; ++round) {
        SCOPED_TRACE("round " + std::to_string(round));
        std::vector<std::function<void()>> queued;
        auto staged = StagedGeometry::stage(
            scene, limit, [&](std::function<void()> copy) { queued.push_back(std::move(copy)); },
            staging, 1000);
        EXPECT_EQ(staging->created(), layout.buffers.size());  // Reused, not created.
        EXPECT_EQ(staged->layout(), layout);
        ASSERT_GT(queued.size(), 2 * layout.buffers.size());
        // Every other piece on a thread of its own; the rest left to the uploading thread.
        std::vector<std::thread> threads;
        for (std::size_t i = 0; i < queued.size(); i += 2) {
            threads.emplace_back(queued[i]);
        }
        const GeometryBuffers copied(context->device(), scene, limit, staged.get());
        for (std::thread& thread : threads) {
            thread.join();
        }
        EXPECT_EQ(sharedBytes(*context, copied), expected);
        staged.reset();
        for (std::size_t i = 1; i < queued.size(); i += 2) {
            queued[i]();  // Claimed: nothing happens.
        }
    }
    // Staged but never uploaded: the pieces still queued do nothing once it is gone.
    std::vector<std::function<void()>> queued;
    auto unused = StagedGeometry::stage(
        scene, limit, [&](std::function<void()> copy) { queued.push_back(std::move(copy)); },
        staging, 1000);
    unused.reset();
    for (const auto& copy : queued) {
        copy();
    }
    EXPECT_TRUE(context->checkNoErrors("staged geometry").ok());
}

}  // namespace
}  // namespace encore::render
