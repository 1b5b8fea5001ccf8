#include "render/VertexBindings.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "core/Bytes.h"
#include "encore/render/RenderEncoder.h"
#include "encore/render/RenderSetup.h"
#include "gpu/Upload.h"
#include "render/GltfToWebGpu.h"

namespace encore::render {

namespace {

// WebGPU's limit on arrayStride (maxVertexBufferArrayStride).
constexpr std::uint32_t kMaxArrayStride = 2048;

struct BoundAttribute {
    scene::Semantic semantic;
    scene::AccessorId accessor;
    wgpu::VertexFormat format;
    std::uint32_t location;
};

}  // namespace

std::vector<std::uint8_t> paddedVertexElements(const scene::SceneData& scene,
                                               scene::AccessorId id,
                                               std::uint32_t& stride) {
    const scene::Accessor& accessor = scene.accessors[id.index()];
    std::vector<std::uint8_t> packed = scene.packedAccessorBytes(id);
    const std::uint32_t elementSize = accessor.elementSize();
    stride = (elementSize + 3) & ~3u;
    if (stride == elementSize) {
        return packed;
    }
    std::vector<std::uint8_t> padded(std::size_t(stride) * accessor.count, 0);
    for (std::uint32_t i = 0; i < accessor.count; ++i) {
        std::memcpy(&padded[std::size_t(i) * stride], &packed[std::size_t(i) * elementSize],
                    elementSize);
    }
    return padded;
}

bool readsInPlace(const scene::Accessor& accessor) {
    return accessor.byteStride % 4 == 0 && accessor.byteOffset % 4 == 0 &&
           accessor.byteStride <= kMaxArrayStride && accessor.byteStride >= accessor.elementSize();
}

GeometryBuffers::GeometryBuffers(wgpu::Device device,
                                 const scene::SceneData& scene,
                                 std::uint64_t maxSharedBufferBytes)
    : mDevice(std::move(device)), mScene(&scene) {
    uploadViews(maxSharedBufferBytes);
    uploadRepackedAccessors();
}

void GeometryBuffers::uploadRepackedAccessors() {
    // Every attribute a shader may read that cannot be bound in place, copied now rather than
    // on first bind: every strategy binds from the same uploads, whichever binds first.
    for (const scene::Mesh& mesh : mScene->meshes) {
        for (const scene::Primitive& primitive : mesh.primitives) {
            for (const scene::VertexAttribute& attribute : primitive.attributes) {
                const scene::AccessorId id = attribute.accessor;
                if (id.index() >= mScene->accessors.size() || mPrivateBuffers.contains(id) ||
                    !shaderLocation(attribute.semantic)) {
                    continue;
                }
                const scene::Accessor& accessor = mScene->accessors[id.index()];
                if (readsInPlace(accessor) || !vertexFormat(accessor)) {
                    continue;  // Bound in place, or refused by bind().
                }
                std::uint32_t stride = 0;
                const auto bytes = paddedVertexElements(*mScene, id, stride);
                const wgpu::Buffer buffer = gpu::createBufferWithData(
                    mDevice, wgpu::BufferUsage::Vertex | wgpu::BufferUsage::Storage, bytes,
                    "repacked accessor " + std::to_string(id.value));
                mUploadedBytes += bytes.size();
                mPrivateBuffers[id] = {buffer, stride};
            }
        }
    }
}

void GeometryBuffers::uploadViews(std::uint64_t maxSharedBufferBytes) {
    // Every view a primitive may read in place: those of in-place attributes and of indices.
    std::vector<scene::BufferViewId> views;
    auto add = [&](scene::AccessorId id, bool indices) {
        if (id.index() >= mScene->accessors.size()) {
            return;
        }
        const scene::Accessor& accessor = mScene->accessors[id.index()];
        if (accessor.view.index() < mScene->bufferViews.size() &&
            (indices || readsInPlace(accessor))) {
            views.push_back(accessor.view);
        }
    };
    for (const scene::Mesh& mesh : mScene->meshes) {
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

    std::uint64_t maxBytes = maxSharedBufferBytes;
    if (maxBytes == 0) {
        wgpu::Limits limits{};
        mDevice.GetLimits(&limits);
        maxBytes = limits.maxBufferSize;
    }
    // Where each view goes: views packed at 4-byte offsets into shared buffers of at most
    // maxBytes each. Then each buffer is created mapped and the views are copied straight into
    // it: gathering them into one vector first copied every byte twice on the device's thread
    // (a tenth of `encore batch`'s upload time).
    struct SharedBuffer {
        std::uint64_t size = 0;
        std::vector<scene::BufferViewId> views;
    };
    std::vector<SharedBuffer> layout;
    for (scene::BufferViewId id : views) {
        const scene::BufferView& view = mScene->bufferViews[id.index()];
        std::uint64_t offset = layout.empty() ? 0 : (layout.back().size + 3) & ~std::uint64_t(3);
        // A view larger than the device's limit on its own was refused before (SceneLimits).
        if (layout.empty() || offset + view.byteLength > maxBytes) {
            layout.emplace_back();
            offset = 0;
        }
        layout.back().size = offset + view.byteLength;
        layout.back().views.push_back(id);
        mViews[id] = {{}, offset, view.byteLength};
    }
    for (const SharedBuffer& shared : layout) {
        // Mapped at creation, so zeroed: the gaps between views read as zeros.
        // Storage too: passes that fetch vertices themselves read the same bytes.
        const wgpu::Buffer buffer = gpu::createBufferFilledBy(
            mDevice,
            wgpu::BufferUsage::Vertex | wgpu::BufferUsage::Index | wgpu::BufferUsage::Storage,
            shared.size, "geometry " + std::to_string(mSharedBuffers.size()),
            [&](std::uint8_t* mapped) {
                for (scene::BufferViewId id : shared.views) {
                    const scene::BufferView& view = mScene->bufferViews[id.index()];
                    const auto& source = mScene->buffers[view.buffer.index()].bytes;
                    // An empty buffer's data() is null: a zero-length view of it copies nothing.
                    copyBytes(mapped + mViews[id].offset, source.data() + view.byteOffset,
                              view.byteLength);
                }
            });
        for (scene::BufferViewId id : shared.views) {
            mViews[id].buffer = buffer;
        }
        mUploadedBytes += shared.size;
        mSharedBuffers.push_back(buffer);
    }
}

const GeometryBuffers::ViewPlacement& GeometryBuffers::viewPlacement(scene::BufferViewId id) const {
    const auto found = mViews.find(id);
    // bind() asks only for views of the scene's primitives, all uploaded by the constructor.
    ENCORE_CHECK(found != mViews.end(),
                 "GeometryBuffers: bufferView " + std::to_string(id.value) + " was not uploaded");
    return found->second;
}

std::optional<GeometryBuffers::SharedPlacement> GeometryBuffers::sharedPlacement(
    scene::AccessorId id) const {
    if (id.index() >= mScene->accessors.size()) {
        return std::nullopt;
    }
    const scene::Accessor& accessor = mScene->accessors[id.index()];
    const auto found = mViews.find(accessor.view);
    if (found == mViews.end()) {
        return std::nullopt;
    }
    const auto buffer =
        std::find_if(mSharedBuffers.begin(), mSharedBuffers.end(),
                     [&](const wgpu::Buffer& b) { return b.Get() == found->second.buffer.Get(); });
    if (buffer == mSharedBuffers.end()) {
        return std::nullopt;
    }
    return SharedPlacement{std::size_t(buffer - mSharedBuffers.begin()),
                           found->second.offset + accessor.byteOffset};
}

Result<PrimitiveBindings> GeometryBuffers::bind(const scene::Primitive& primitive,
                                                std::span<const scene::Semantic> semantics) const {
    PrimitiveBindings bindings;
    bindings.topology = primitive.topology;
    bindings.vertexCount = primitive.vertexCount;

    std::vector<BoundAttribute> attributes;
    for (scene::Semantic semantic : semantics) {
        const auto accessorId = primitive.attribute(semantic);
        const auto location = shaderLocation(semantic);
        if (!accessorId || !location) {
            continue;
        }
        const auto format = vertexFormat(mScene->accessors[accessorId->index()]);
        if (!format) {
            return makeError(ErrorCode::Unsupported,
                             "Accessor " + std::to_string(accessorId->value) + " (" +
                                 std::string(scene::semanticName(semantic)) +
                                 ") has no WebGPU vertex format.");
        }
        attributes.push_back({semantic, *accessorId, *format, *location});
    }

    // Group in-place attributes by (view, stride), in offset order, so interleaved ones are
    // adjacent; the rest get private padded copies.
    auto inPlace = [&](const BoundAttribute& attribute) {
        return readsInPlace(mScene->accessors[attribute.accessor.index()]);
    };
    std::stable_sort(attributes.begin(), attributes.end(), [&](const auto& a, const auto& b) {
        const scene::Accessor& x = mScene->accessors[a.accessor.index()];
        const scene::Accessor& y = mScene->accessors[b.accessor.index()];
        return std::tie(x.view, x.byteStride, x.byteOffset) <
               std::tie(y.view, y.byteStride, y.byteOffset);
    });

    struct Slot {
        VertexBufferBinding binding;
        VertexBufferKey key;
        scene::BufferViewId view;
    };
    std::vector<Slot> slots;
    for (const BoundAttribute& attribute : attributes) {
        const scene::Accessor& accessor = mScene->accessors[attribute.accessor.index()];
        if (!inPlace(attribute)) {
            const auto repacked = mPrivateBuffers.find(attribute.accessor);
            // The constructor repacked every attribute with a shader location and a format.
            ENCORE_CHECK(repacked != mPrivateBuffers.end(),
                         "GeometryBuffers: accessor " + std::to_string(attribute.accessor.value) +
                             " was not repacked");
            const auto& [buffer, stride] = repacked->second;
            Slot slot{{buffer, 0, buffer.GetSize()}, {}, {}};
            slot.key.arrayStride = stride;
            slot.key.attributes[slot.key.attributeCount++] = {attribute.format, 0,
                                                              attribute.location};
            slots.push_back(slot);
            continue;
        }
        // Offsets below are within the shared buffer; the slot's view is the attribute's.
        const ViewPlacement& view = viewPlacement(accessor.view);
        const std::uint64_t offset = view.offset + accessor.byteOffset;
        // WebGPU needs offset + size <= arrayStride for every attribute of a slot.
        const bool joinsLast =
            !slots.empty() && slots.back().view == accessor.view &&
            slots.back().key.arrayStride == accessor.byteStride &&
            offset - slots.back().binding.offset + accessor.elementSize() <= accessor.byteStride &&
            slots.back().key.attributeCount < VertexBufferKey::kMaxAttributes;
        if (!joinsLast) {
            Slot slot{{view.buffer, offset, view.offset + view.length - offset}, {}, accessor.view};
            slot.key.arrayStride = accessor.byteStride;
            slots.push_back(slot);
        }
        Slot& slot = slots.back();
        const auto relative = static_cast<std::uint32_t>(offset - slot.binding.offset);
        slot.key.attributes[slot.key.attributeCount++] = {attribute.format, relative,
                                                          attribute.location};
    }

    for (Slot& slot : slots) {
        std::sort(slot.key.attributes, slot.key.attributes + slot.key.attributeCount,
                  [](const auto& a, const auto& b) { return a.shaderLocation < b.shaderLocation; });
    }
    std::sort(slots.begin(), slots.end(), [](const Slot& a, const Slot& b) {
        return a.key.attributes[0].shaderLocation < b.key.attributes[0].shaderLocation;
    });
    for (const Slot& slot : slots) {
        bindings.vertexBuffers.push_back(slot.binding);
        bindings.layout.buffers[bindings.layout.bufferCount++] = slot.key;
    }

    if (primitive.indices) {
        const scene::Accessor& indices = mScene->accessors[primitive.indices->index()];
        const ViewPlacement& view = viewPlacement(indices.view);
        const std::uint64_t offset = view.offset + indices.byteOffset;
        bindings.indices = IndexBufferBinding{view.buffer, indexFormat(indices), offset,
                                              indices.count, view.offset + view.length - offset};
    }
    return bindings;
}

}  // namespace encore::render

namespace encore::render {

PipelineKey meshPipelineKey(const RenderSetup& setup,
                            const PrimitiveBindings& bindings,
                            const shaders::ShaderVariantKey& shader) {
    PipelineKey key = bindings.layout;
    key.topology = primitiveTopology(bindings.topology);
    if (bindings.indices && isStrip(bindings.topology)) {
        key.stripIndexFormat = bindings.indices->format;
    }
    key.colorFormat = setup.colorFormat;
    key.depthFormat = setup.depthFormat;
    key.sampleCount = setup.sampleCount;
    key.shader = shader;
    if (shader.materials) {
        key.shader.passTargets = setup.passTargets;  // Frames without pass targets: 0.
    }
    return key;
}

void bindGeometry(RenderEncoder& encoder, const PrimitiveBindings& bindings) {
    for (std::uint32_t slot = 0; slot < bindings.vertexBuffers.size(); ++slot) {
        encoder.setVertexBuffer(slot, bindings.vertexBuffers[slot].buffer,
                                bindings.vertexBuffers[slot].offset,
                                bindings.vertexBuffers[slot].size);
    }
    if (bindings.indices) {
        encoder.setIndexBuffer(bindings.indices->buffer, bindings.indices->format,
                               bindings.indices->offset, bindings.indices->size);
    }
}

void drawGeometry(RenderEncoder& encoder,
                  const PrimitiveBindings& bindings,
                  std::uint32_t instanceCount,
                  std::uint32_t firstInstance) {
    if (bindings.indices) {
        encoder.drawIndexed(bindings.indices->count, instanceCount, 0, 0, firstInstance,
                            bindings.topology);
    } else {
        encoder.draw(bindings.vertexCount, instanceCount, 0, firstInstance, bindings.topology);
    }
}

}  // namespace encore::render
