// EXT_meshopt_compression: a compressed bufferView names a source range in another buffer and
// how to decode it. The decoded bytes get a buffer of their own and the view is pointed at it,
// so accessors keep their indices and offsets and never see the compression.

#include <meshoptimizer.h>

#include "scene/LoadContext.h"

namespace encore::scene {
namespace {

Result<std::vector<std::uint8_t>> decodeView(const GltfMeshoptCompression& compression,
                                             std::span<const std::uint8_t> source,
                                             const std::string& name) {
    const std::uint64_t count = compression.count;
    const std::uint64_t stride = compression.byteStride;
    const auto size = mulAdd(count, stride, 0);
    if (!size || *size > kMaxMaterializedBytes) {
        return makeError(ErrorCode::LimitExceeded, name + " decodes to too many bytes (count " +
                                                       std::to_string(count) + " x byteStride " +
                                                       std::to_string(stride) + ").");
    }
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(*size));
    int status = -1;
    const auto& mode = compression.mode;
    if (mode == "ATTRIBUTES") {
        if (stride == 0 || stride % 4 != 0 || stride > 256) {
            return makeError(ErrorCode::InvalidFormat,
                             name + " has an invalid byteStride for ATTRIBUTES mode (" +
                                 std::to_string(stride) + ").");
        }
        status =
            meshopt_decodeVertexBuffer(bytes.data(), count, stride, source.data(), source.size());
    } else if (mode == "TRIANGLES" || mode == "INDICES") {
        if (stride != 2 && stride != 4) {
            return makeError(ErrorCode::InvalidFormat, name + " has an invalid byteStride for " +
                                                           mode + " mode (" +
                                                           std::to_string(stride) + ").");
        }
        if (mode == "TRIANGLES") {
            if (count % 3 != 0) {
                return makeError(ErrorCode::InvalidFormat,
                                 name + " has a TRIANGLES count that is not a multiple of 3 (" +
                                     std::to_string(count) + ").");
            }
            status = meshopt_decodeIndexBuffer(bytes.data(), count, stride, source.data(),
                                               source.size());
        } else {
            status = meshopt_decodeIndexSequence(bytes.data(), count, stride, source.data(),
                                                 source.size());
        }
    } else {
        return makeError(ErrorCode::Unsupported,
                         name + " uses an unknown compression mode ('" + mode + "').");
    }
    if (status != 0) {
        return makeError(ErrorCode::InvalidFormat, name +
                                                       " cannot be decoded (meshoptimizer "
                                                       "error " +
                                                       std::to_string(status) + ").");
    }

    const auto& filter = compression.filter;
    if (filter == "OCTAHEDRAL") {
        if (stride != 4 && stride != 8) {
            return makeError(ErrorCode::InvalidFormat, name +
                                                           " uses the OCTAHEDRAL filter with "
                                                           "a byteStride other than 4 or 8 (" +
                                                           std::to_string(stride) + ").");
        }
        meshopt_decodeFilterOct(bytes.data(), count, stride);
    } else if (filter == "QUATERNION") {
        if (stride != 8) {
            return makeError(ErrorCode::InvalidFormat,
                             name + " uses the QUATERNION filter with a byteStride other than 8 (" +
                                 std::to_string(stride) + ").");
        }
        meshopt_decodeFilterQuat(bytes.data(), count, stride);
    } else if (filter == "EXPONENTIAL") {
        if (stride % 4 != 0) {
            return makeError(ErrorCode::InvalidFormat,
                             name +
                                 " uses the EXPONENTIAL filter with a byteStride that is not "
                                 "a multiple of 4 (" +
                                 std::to_string(stride) + ").");
        }
        meshopt_decodeFilterExp(bytes.data(), count, stride);
    } else if (filter != "NONE") {
        return makeError(ErrorCode::Unsupported,
                         name + " uses an unknown compression filter ('" + filter + "').");
    }
    return bytes;
}

}  // namespace

Result<void> decodeMeshoptViews(LoadContext& context) {
    auto& scene = context.scene;
    const auto& views = context.document.bufferViews;
    for (std::size_t i = 0; i < views.size(); ++i) {
        if (!views[i].meshopt) {
            continue;
        }
        const GltfMeshoptCompression& compression = *views[i].meshopt;
        const std::string name = "bufferView " + std::to_string(i) + " (EXT_meshopt_compression)";
        const auto& sourceBuffer = scene.buffers[compression.buffer].bytes;
        const auto end = mulAdd(1, compression.byteOffset, compression.byteLength);
        if (!end || *end > sourceBuffer.size()) {
            return makeError(ErrorCode::InvalidFormat,
                             name + " reads past the end of buffer " +
                                 std::to_string(compression.buffer) + " (offset " +
                                 std::to_string(compression.byteOffset) + " + length " +
                                 std::to_string(compression.byteLength) + " > " +
                                 std::to_string(sourceBuffer.size()) + " bytes).");
        }
        const auto source = std::span(sourceBuffer)
                                .subspan(static_cast<std::size_t>(compression.byteOffset),
                                         static_cast<std::size_t>(compression.byteLength));
        std::vector<std::uint8_t> decoded;
        ENCORE_TRY_ASSIGN(decoded, decodeView(compression, source, name));

        BufferView& view = scene.bufferViews[i];
        if (view.byteLength > decoded.size()) {
            return makeError(ErrorCode::InvalidFormat,
                             name + " is longer than its decoded data (byteLength " +
                                 std::to_string(view.byteLength) + " > count x byteStride " +
                                 std::to_string(decoded.size()) + ").");
        }
        view.buffer = BufferId(scene.buffers.size());
        view.byteOffset = 0;
        scene.buffers.push_back(
            Buffer{"EXT_meshopt_compression bufferView " + std::to_string(i), std::move(decoded)});
    }
    return {};
}

}  // namespace encore::scene
