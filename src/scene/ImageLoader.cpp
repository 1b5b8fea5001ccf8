// Images are optional for drawing: a missing or undecodable one is a warning and the renderer
// substitutes a default texture (an error only in strict mode). Without decoding, external files
// are still checked for existence so that both modes report the same missing files. A texture
// draws its EXT_texture_webp image when that decodes, else its core source; KTX2 images
// (KHR_texture_basisu) are never decoded, and neither is a fallback no texture draws.

#include <algorithm>
#include <filesystem>
#include <optional>
#include <string_view>
#include <vector>

#include "core/FileIO.h"
#include "encore/image/ImageCodec.h"
#include "image/FittedDecode.h"
#include "scene/LoadContext.h"

namespace encore::scene {
namespace {

Result<std::vector<std::uint8_t>> imageBytes(const LoadContext& context,
                                             const GltfImage& image,
                                             std::size_t index) {
    if (image.uri) {
        return readUri(*image.uri, context.uriScope());
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
    ENCORE_TRY_ASSIGN(path, resolveUriPath(*image.uri, context.uriScope()));
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

// "image 3 ('wood.png')", as messages name an image.
std::string imageLabel(const GltfImage& source, std::size_t index) {
    const bool external = source.uri && !isDataUri(*source.uri);
    return "image " + std::to_string(index) + " ('" +
           (external              ? *source.uri
            : source.name.empty() ? "embedded"
                                  : source.name) +
           "')";
}

// The reason of an error as a clause ending in a full stop.
std::string reasonOf(const Error& problem) {
    std::string reason = problem.message;
    if (!reason.empty() && reason.back() != '.') {
        reason += '.';
    }
    return reason;
}

// Which images a material samples as sRGB colour (base colour, emissive, specular and sheen
// colour, the specular-glossiness diffuse and specular): a downscale averages those in linear
// light, the others (normals, roughness) as they are.
std::vector<bool> srgbImages(const GltfDocument& document) {
    std::vector<bool> srgb(document.images.size(), false);
    constexpr std::string_view kColorSlots[] = {
        "baseColorTexture",  "emissiveTexture", "specularColorTexture",
        "sheenColorTexture", "diffuseTexture",  "specularGlossinessTexture"};
    for (const GltfMaterial& material : document.materials) {
        for (const GltfMaterialTextureSlot& slot : materialTextureSlots(material)) {
            const bool color = std::any_of(
                std::begin(kColorSlots), std::end(kColorSlots),
                [&](std::string_view name) { return std::string_view(slot.slot).ends_with(name); });
            if (!color || slot.info->index >= document.textures.size()) {
                continue;
            }
            const GltfTexture& texture = document.textures[slot.info->index];
            for (const auto& image : {texture.source, texture.webpSource}) {
                if (image && *image < srgb.size()) {
                    srgb[*image] = true;
                }
            }
        }
    }
    return srgb;
}

// Decodes (or, without decoding, checks) each image at most once and remembers the outcome.
class ImageDecoder {
  public:
    explicit ImageDecoder(LoadContext& context)
        : mContext(context),
          mDone(context.document.images.size(), false),
          mProblems(context.document.images.size()),
          mSrgb(srgbImages(context.document)) {}

    // Nothing when the image is usable; else why not.
    const std::optional<Error>& load(std::size_t index) {
        if (mDone[index]) {
            return mProblems[index];
        }
        mDone[index] = true;
        const GltfImage& source = mContext.document.images[index];
        Image& image = mContext.scene.images[index];
        std::optional<Error>& problem = mProblems[index];
        if (!mContext.options.decodeImages) {
            if (auto exists = checkImageExists(mContext, source); !exists.ok()) {
                problem = exists.error();
            }
        } else if (auto bytes = imageBytes(mContext, source, index); !bytes.ok()) {
            problem = bytes.error();
        } else if (auto decoded = image::decodeImageWithin(
                       *bytes, mContext.options.maxImageDimension,
                       mSrgb[index] ? image::PixelEncoding::Srgb : image::PixelEncoding::Linear);
                   !decoded.ok()) {
            problem = decoded.error();
        } else {
            image.width = decoded->image.width;
            image.height = decoded->image.height;
            image.sourceWidth = decoded->source.width;
            image.sourceHeight = decoded->source.height;
            image.rgba8 = std::move(decoded->image.pixels);
        }
        return problem;
    }

  private:
    LoadContext& mContext;
    std::vector<bool> mDone;
    std::vector<std::optional<Error>> mProblems;
    std::vector<bool> mSrgb;  // Downscaled averaging colour in linear light.
};

// Each texture's drawn image: EXT_texture_webp's when it decodes, else the core source. A WebP
// image that fails falls back with a warning, or is an error when the asset requires the
// extension (there is then no fallback to trust).
Result<void> chooseTextureImages(LoadContext& context, ImageDecoder& decoder) {
    const GltfDocument& document = context.document;
    const bool webpRequired =
        std::find(document.extensionsRequired.begin(), document.extensionsRequired.end(),
                  "EXT_texture_webp") != document.extensionsRequired.end();
    context.textureImages.assign(document.textures.size(), std::nullopt);
    for (std::size_t t = 0; t < document.textures.size(); ++t) {
        const GltfTexture& texture = document.textures[t];
        context.textureImages[t] = texture.source;
        if (!texture.webpSource) {
            continue;
        }
        ENCORE_TRY(context.checkCancelled());
        const std::size_t webp = *texture.webpSource;
        const std::optional<Error>& problem = decoder.load(webp);
        if (!problem) {
            context.textureImages[t] = texture.webpSource;
            continue;
        }
        const std::string what = "texture " + std::to_string(t) + "'s EXT_texture_webp " +
                                 imageLabel(document.images[webp], webp) + " cannot be read (" +
                                 reasonOf(*problem) + ")";
        if (webpRequired) {
            return makeError(problem->code,
                             what +
                                 "; the asset requires EXT_texture_webp, so no fallback image "
                                 "stands in for it.");
        }
        ENCORE_TRY(context.warn(
            problem->code, what + (texture.source ? "; drawing its fallback source, image " +
                                                        std::to_string(*texture.source) + "."
                                                  : "; drawing it with a default texture (it has "
                                                    "no fallback source).")));
    }
    return {};
}

}  // namespace

Result<void> loadImages(LoadContext& context) {
    const auto& images = context.document.images;
    context.scene.images.resize(images.size());
    for (std::size_t i = 0; i < images.size(); ++i) {
        const GltfImage& source = images[i];
        const bool external = source.uri && !isDataUri(*source.uri);
        context.scene.images[i].name = external ? *source.uri : "image " + std::to_string(i);
    }
    ImageDecoder decoder(context);
    ENCORE_TRY(chooseTextureImages(context, decoder));
    ENCORE_TRY(context.checkModelBytes("decoding the textures' WebP images"));

    // Decoded: the images textures draw, and those no texture refers to at all (as every image
    // was before texture extensions: a caller may still use them). Not decoded: KTX2 images
    // (KHR_texture_basisu) and fallbacks whose WebP image stood in for them.
    std::vector<bool> referenced(images.size(), false);
    std::vector<bool> drawn(images.size(), false);
    for (std::size_t t = 0; t < context.document.textures.size(); ++t) {
        const GltfTexture& texture = context.document.textures[t];
        for (const auto& image : {texture.source, texture.webpSource, texture.basisuSource}) {
            if (image) {
                referenced[*image] = true;
            }
        }
        if (const auto image = context.textureImages[t]) {
            drawn[*image] = true;
        }
    }
    for (std::size_t i = 0; i < images.size(); ++i) {
        if (!drawn[i] && referenced[i]) {
            continue;
        }
        ENCORE_TRY(context.checkCancelled());  // Each image may take a while to decode.
        if (const std::optional<Error>& problem = decoder.load(i)) {
            ENCORE_TRY(context.warn(problem->code, imageLabel(images[i], i) + " cannot be read (" +
                                                       reasonOf(*problem) +
                                                       "); drawing it with a default texture."));
        }
        ENCORE_TRY(context.checkModelBytes("decoding " + imageLabel(images[i], i)));
    }
    return {};
}

}  // namespace encore::scene
