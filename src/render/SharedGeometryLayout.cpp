#include "render/SharedGeometryLayout.h"

#include <algorithm>

namespace encore::render {

namespace {

// WebGPU's limit on arrayStride (maxVertexBufferArrayStride).
constexpr std::uint32_t kMaxArrayStride = 2048;

}  // namespace

bool readsInPlace(const scene::Accessor& accessor) {
    return accessor.byteStride % 4 == 0 && accessor.byteOffset % 4 == 0 &&
           accessor.byteStride <= kMaxArrayStride && accessor.byteStride >= accessor.elementSize();
}

SharedGeometryLayout sharedGeometryLayout(const scene::SceneData& scene,
                                          std::uint64_t maxBufferBytes) {
    std::vector<scene::BufferViewId> views;
    auto add = [&](scene::AccessorId id, bool indices) {
        if (id.index() >= scene.accessors.size()) {
            return;
        }
        const scene::Accessor& accessor = scene.accessors[id.index()];
        if (accessor.view.index() < scene.bufferViews.size() &&
            (indices || readsInPlace(accessor))) {
            views.push_back(accessor.view);
        }
    };
    for (const scene::Mesh& mesh : scene.meshes) {
        for (const scene::Primitive& primitive : mesh.primitives) {
            for (const scene::VertexAttribute& attribute : primitive.attributes) {
                add(attribute.accessor, false);
            }
            if (primitive.indices) {
                add(*primitive.indices, true);
            }
        }
    }
    std::sort(views.begin(), views.end());
    views.erase(std::unique(views.begin(), views.end()), views.end());

    SharedGeometryLayout layout;
    for (scene::BufferViewId id : views) {
        const scene::BufferView& view = scene.bufferViews[id.index()];
        auto& buffers = layout.buffers;
        std::uint64_t offset = buffers.empty() ? 0 : (buffers.back().size + 3) & ~std::uint64_t(3);
        // A view larger than the device's limit on its own was refused before (SceneLimits).
        if (buffers.empty() || offset + view.byteLength > maxBufferBytes) {
            buffers.emplace_back();
            offset = 0;
        }
        buffers.back().size = offset + view.byteLength;
        buffers.back().views.push_back({id, offset, view.byteLength});
    }
    return layout;
}

}  // namespace encore::render
