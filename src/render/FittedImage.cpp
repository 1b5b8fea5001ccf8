#include "render/FittedImage.h"

#include "core/Log.h"

namespace encore::render {

FittedImage fitImage(const std::string& description,
                     const scene::Image& image,
                     bool srgb,
                     std::uint32_t maxDimension) {
    const image::ImageSize original{image.width, image.height};
    FittedImage fitted{image::fitWithin(original, maxDimension), image.rgba8.data(), {}};
    if (fitted.size == original) {
        return fitted;
    }
    fitted.downscaled =
        image::downscaleRgba8(image.rgba8, original, fitted.size,
                              srgb ? image::PixelEncoding::Srgb : image::PixelEncoding::Linear);
    logWarning(description + " is " + std::to_string(original.width) + "x" +
               std::to_string(original.height) +
               " pixels, larger than the device's maxTextureDimension2D (" +
               std::to_string(maxDimension) + "); downscaled to " +
               std::to_string(fitted.size.width) + "x" + std::to_string(fitted.size.height) + ".");
    return fitted;
}

}  // namespace encore::render
