#pragma once

// Encoded images for texture tests, made in the test: solid PNGs (Encore's encoder) and WebP
// images (libwebp's encoder, lossless or lossy), embedded into a GltfBuilder's buffer.

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "GltfBuilder.h"
#include "encore/image/ImageCodec.h"
#include "encore/scene/SceneData.h"

namespace encore::test {

// A `width` x `height` image of one colour.
image::ImageRgba8 solidImage(std::array<std::uint8_t, 4> rgba,
                             std::uint32_t width = 1,
                             std::uint32_t height = 1);

// The same as a decoded scene image (for Renderer::replaceBaseColorImage, or a SceneData's
// images), named `name`.
scene::Image solidSceneImage(std::array<std::uint8_t, 4> rgba,
                             std::uint32_t width = 2,
                             std::uint32_t height = 2,
                             const std::string& name = "solid");

std::vector<std::uint8_t> encodePngBytes(const image::ImageRgba8& image);
// libwebp: lossless (WebPEncodeLosslessRGBA, exact pixels) or lossy at `quality` (0-100).
std::vector<std::uint8_t> encodeWebpBytes(const image::ImageRgba8& image,
                                          bool lossless = true,
                                          float quality = 90.0f);

// Appends an image held in a bufferView of buffer 0; returns its index.
std::uint32_t addEmbeddedImage(GltfBuilder& builder,
                               std::span<const std::uint8_t> bytes,
                               const std::string& mimeType);

}  // namespace encore::test
