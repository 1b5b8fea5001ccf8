#include "render/VertexBindings.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "core/Bytes.h"
#include "gpu/ResourcePool.h"
#include "gpu/Upload.h"
#include "render/GltfToWebGpu.h"
#include "render/RenderEncoder.h"
#include "render/RenderSetup.h"
#include "render/SharedGeometryLayout.h"
#include "render/StagedGeometry.h"

namespace encore::render {

namespace {

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

GeometryBuffers::GeometryBuffers(wgpu::Device device,
                                 const scene::SceneData& scene,
                                 std::uint64_t maxSharedBufferBytes,
                                 StagedGeometry* staged,
                                 gpu::ResourcePool* pool,
                                 wgpu::CommandEncoder uploads)
    : mDevice(std::move(device)), mScene(&scene) {
    uploadViews(maxSharedBufferBytes, staged, pool, std::move(uploads));
    uploadRepackedAccessors();
}

void GeometryBuffers::giveBackTo(gpu::ResourcePool& pool) {
    for (wgpu::Buffer& buffer : mSharedBuffers) {
        pool.giveBack(std::move(buffer));
    }
    mSharedBuffers.clear();
    mViews.clear();
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

void GeometryBuffers::uploadViews(std::uint64_t maxSharedBufferBytes,
                                  StagedGeometry* staged,
                                  gpu::ResourcePool* pool,
                                  wgpu::CommandEncoder uploads) {
    std::uint64_t maxBytes = maxSharedBufferBytes;
    if (maxBytes == 0) {
        wgpu::Limits limits{};
        mDevice.GetLimits(&limits);
        maxBytes = limits.maxBufferSize;
    }
    const SharedGeometryLayout layout = sharedGeometryLayout(*mScene, maxBytes);
    if (staged && staged->layout() != layout) {
        staged = nullptr;  // Staged for another device's limit: upload here instead.
    }
    // Storage too: passes that fetch vertices themselves read the same bytes; CopySrc for
    // reading them back (tests compare the two uploads below).
    const wgpu::BufferUsage usage = wgpu::BufferUsage::Vertex | wgpu::BufferUsage::Index |
                                    wgpu::BufferUsage::Storage | wgpu::BufferUsage::CopySrc;
    wgpu::CommandEncoder copies = uploads;
    for (std::size_t index = 0; index < layout.buffers.size(); ++index) {
        const SharedGeometryLayout::Buffer& shared = layout.buffers[index];
        const std::string label = "geometry " + std::to_string(index);
        const wgpu::Buffer source = staged ? staged->copySource(index) : nullptr;
        wgpu::Buffer buffer;
        if (source) {
            // The staging buffer's bytes, gaps zeroed, over the whole (4-byte-rounded) buffer:
            // Dawn then has nothing to clear.
            buffer = pool ? pool->buffer(usage | wgpu::BufferUsage::CopyDst, shared.size, label)
                          : gpu::createBuffer(mDevice, usage | wgpu::BufferUsage::CopyDst,
                                              shared.size, label);
            if (!copies) {
                copies = mDevice.CreateCommandEncoder();
            }
            copies.CopyBufferToBuffer(source, 0, buffer, 0, buffer.GetSize());
        } else if (pool) {
            // A kept buffer is written through the queue: the views gathered, the gaps zeroed.
            std::vector<std::uint8_t> bytes(shared.size, 0);
            for (const SharedGeometryLayout::View& view : shared.views) {
                const scene::BufferView& source = mScene->bufferViews[view.id.index()];
                const auto& data = mScene->buffers[source.buffer.index()].bytes;
                copyBytes(bytes.data() + view.offset, data.data() + source.byteOffset, view.length);
            }
            buffer = pool->bufferWithData(mDevice.GetQueue(), usage | wgpu::BufferUsage::CopyDst,
                                          bytes, label);
        } else {
            // Mapped at creation, so zeroed: the gaps between views read as zeros. The views
            // are copied straight into it: gathering them into one vector first copied every
            // byte twice on the device's thread (a tenth of `encore batch`'s upload time).
            buffer = gpu::createBufferFilledBy(
                mDevice, usage, shared.size, label, [&](std::uint8_t* mapped) {
                    for (const SharedGeometryLayout::View& view : shared.views) {
                        const scene::BufferView& source = mScene->bufferViews[view.id.index()];
                        const auto& bytes = mScene->buffers[source.buffer.index()].bytes;
                        // An empty buffer's data() is null: a zero-length view copies nothing.
                        copyBytes(mapped + view.offset, bytes.data() + source.byteOffset,
                                  view.length);
                    }
                });
        }
        for (const SharedGeometryLayout::View& view : shared.views) {
            mViews[view.id] = {buffer, view.offset, view.length};
        }
        mUploadedBytes += shared.size;
        mSharedBuffers.push_back(buffer);
    }
    if (copies && !uploads) {
        const wgpu::CommandBuffer commands = copies.Finish();
        mDevice.GetQueue().Submit(1, &commands);
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
