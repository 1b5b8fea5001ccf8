// Images are optional for drawing: a missing or undecodable one is a warning and the renderer
// substitutes a default texture (an error only in strict mode). Without decoding, external files
// are still checked for existence so that both modes report the same missing files.

#include <filesystem>

#include "core/FileIO.h"
#include "encore/image/ImageCodec.h"
#include "scene/LoadContext.h"

namespace encore::scene {
namespace {

Result<std::vector<std::uint8_t>> imageBytes(const LoadContext& context,
                                             const GltfImage& image,
                                             std::size_t index) {
    if (image.uri) {
        return readUri(*image.uri, context.baseDirectory);
    }
    if (image.bufferView) {
        const SceneData& scene = context.scene;
        const BufferView& view = scene.bufferViews[*image.bufferView];
        const auto& buffer = scene.buffers[view.buffer.index()].bytes;
        if (view.byteLength > buffer.size() || view.byteOffset > buffer.size() - view.byteLength) {
            return makeError(ErrorCode::InvalidFormat,
                             "bufferView " + std::to_string(*image.bufferView) +
                                 " has no data (it lies in an unloaded buffer)");
        }
        const auto begin = buffer.begin() + static_cast<std::ptrdiff_t>(view.byteOffset);
        return std::vector<std::uint8_t>(begin,
                                         begin + static_cast<std::ptrdiff_t>(view.byteLength));
    }
    return makeError(ErrorCode::InvalidFormat,
                     "image " + std::to_string(index) + " has neither a uri nor a bufferView");
}

// Whether the external file behind an image uri exists; data: and bufferView images count as
// present (checking them means decoding them).
Result<void> checkImageExists(const LoadContext& context, const GltfImage& image) {
    if (!image.uri || isDataUri(*image.uri)) {
        return {};
    }
    std::filesystem::path path;
    ENCORE_TRY_ASSIGN(path, resolveUriPath(*image.uri, context.baseDirectory));
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) {
        return makeError(ErrorCode::FileNotFound, "File '" + path.string() + "' does not exist.");
    }
    if (!std::filesystem::is_regular_file(path, ec)) {
        return makeError(ErrorCode::FileUnreadable,
                         "File '" + path.string() + "' is not a regular file.");
    }
    return {};
}

}  // namespace

Result<void> loadImages(LoadContext& context) {
    const auto& images = context.document.images;
    context.scene.images.resize(images.size());
    for (std::size_t i = 0; i < images.size(); ++i) {
        const GltfImage& source = images[i];
        Image& image = context.scene.images[i];
        const bool external = source.uri && !isDataUri(*source.uri);
        image.name = external ? *source.uri : "image " + std::to_string(i);
        const std::string label = "image " + std::to_string(i) + " ('" +
                                  (external              ? *source.uri
                                   : source.name.empty() ? "embedded"
                                                         : source.name) +
                                  "')";

        std::optional<Error> problem;
        if (!context.options.decodeImages) {
            if (auto exists = checkImageExists(context, source); !exists.ok()) {
                problem = exists.error();
            }
        } else if (auto bytes = imageBytes(context, source, i); !bytes.ok()) {
            problem = bytes.error();
        } else if (auto decoded = image::decodeImage(*bytes); !decoded.ok()) {
            problem = decoded.error();
        } else {
            image.width = decoded->width;
            image.height = decoded->height;
            image.rgba8 = std::move(decoded->pixels);
        }
        if (problem) {
            std::string reason = problem->message;
            if (!reason.empty() && reason.back() != '.') {
                reason += '.';
            }
            ENCORE_TRY(context.warn(problem->code, label + " cannot be read (" + reason +
                                                       "); drawing it with a default texture."));
        }
    }
    return {};
}

}  // namespace encore::scene
