#include "TextureFixtures.h"

#include <webp/encode.h>

#include <gtest/gtest.h>

namespace encore::test {

image::ImageRgba8 solidImage(std::array<std::uint8_t, 4> rgba,
                             std::uint32_t width,
                             std::uint32_t height) {
    image::ImageRgba8 image;
    image.width = width;
    image.height = height;
    for (std::uint32_t i = 0; i < width * height; ++i) {
        image.pixels.insert(image.pixels.end(), rgba.begin(), rgba.end());
    }
    return image;
}

scene::Image solidSceneImage(std::array<std::uint8_t, 4> rgba,
                             std::uint32_t width,
                             std::uint32_t height,
                             const std::string& name) {
    scene::Image image;
    image.name = name;
    image.width = width;
    image.height = height;
    image.rgba8 = solidImage(rgba, width, height).pixels;
    return image;
}

std::vector<std::uint8_t> encodePngBytes(const image::ImageRgba8& image) {
    auto png = image::encodePng(image);
    EXPECT_TRUE(png.ok());
    return png.ok() ? std::move(*png) : std::vector<std::uint8_t>{};
}

std::vector<std::uint8_t> encodeWebpBytes(const image::ImageRgba8& image,
                                          bool lossless,
                                          float quality) {
    std::uint8_t* output = nullptr;
    const int stride = int(image.width) * 4;
    const std::size_t size = lossless
                                 ? WebPEncodeLosslessRGBA(image.pixels.data(), int(image.width),
                                                          int(image.height), stride, &output)
                                 : WebPEncodeRGBA(image.pixels.data(), int(image.width),
                                                  int(image.height), stride, quality, &output);
    EXPECT_GT(size, 0u) << "libwebp could not encode the test image";
    std::vector<std::uint8_t> bytes(output, output + size);
    WebPFree(output);
    return bytes;
}

std::uint32_t addEmbeddedImage(GltfBuilder& builder,
                               std::span<const std::uint8_t> bytes,
                               const std::string& mimeType) {
    const std::uint32_t view = builder.addBufferView(bytes);
    auto& images = builder.json()["images"];
    images.push_back({{"bufferView", view}, {"mimeType", mimeType}});
    return static_cast<std::uint32_t>(images.size() - 1);
}

}  // namespace encore::test
