#pragma once

// An image made to fit a device's maxTextureDimension2D: the image itself when it fits,
// otherwise a box-filtered copy with the same aspect ratio (image/ImageResize.h) and a warning
// naming the image and both sizes. Textures stay usable where failing would lose the model.

#include <cstdint>
#include <string>
#include <vector>

#include "encore/scene/SceneData.h"
#include "image/ImageResize.h"

namespace encore::render {

struct FittedImage {
    image::ImageSize size;
    const std::uint8_t* source = nullptr;  // The original pixels, when they fit.
    ReusedBytes downscaled;                // Otherwise the copy.

    const std::uint8_t* pixels() const { return downscaled.empty() ? source : downscaled.data(); }
};

// `description` names the image in the warning ("image 3 ('albedo.png')"). `image` must hold
// width * height * 4 bytes and outlive the result.
FittedImage fitImage(const std::string& description,
                     const scene::Image& image,
                     bool srgb,
                     std::uint32_t maxDimension);

}  // namespace encore::render
