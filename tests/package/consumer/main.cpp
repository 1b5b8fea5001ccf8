// Uses Encore as an installed package would be used: writes a one-triangle glTF, loads it,
// renders it headless with render bundles and checks that the triangle covers the centre of the
// image while the corner keeps the background. Exits 0 on success; prints why otherwise.
//
// It includes every root of the API (scripts/api-headers.py), so that a public header reaching
// a header that is not installed fails to compile here.

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "encore/batch/Batch.h"
#include "encore/core/Result.h"
#include "encore/gpu/Context.h"
#include "encore/image/HdrImage.h"
#include "encore/image/ImageCodec.h"
#include "encore/render/Renderer.h"
#include "encore/scene/SceneData.h"

namespace {

int fail(const std::string& what) {
    std::fprintf(stderr, "encore_consumer: %s\n", what.c_str());
    return 1;
}

// A red, double-sided triangle in the XY plane: positions and 16-bit indices in triangle.bin.
void writeTriangle(const std::filesystem::path& gltf) {
    const std::array<float, 9> positions = {-1.0f, -1.0f, 0.0f, 1.0f, -1.0f,
                                            0.0f,  0.0f,  1.0f, 0.0f};
    const std::array<std::uint16_t, 3> indices = {0, 1, 2};
    std::ofstream bin(gltf.parent_path() / "triangle.bin", std::ios::binary);
    bin.write(reinterpret_cast<const char*>(positions.data()), sizeof(positions));
    bin.write(reinterpret_cast<const char*>(indices.data()), sizeof(indices));
    std::ofstream(gltf) << R"({
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
  "materials": [{"doubleSided": true,
                 "pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 1], "metallicFactor": 0}}],
  "buffers": [{"uri": "triangle.bin", "byteLength": 42}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                  {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [-1, -1, 0], "max": [1, 1, 0]},
                {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]
})";
}

}  // namespace

int main(int argc, char** argv) {
    using namespace encore;
    if (argc != 2) {
        return fail("usage: encore_consumer WORK_DIRECTORY");
    }
    const std::filesystem::path work = argv[1];
    std::filesystem::create_directories(work);
    writeTriangle(work / "triangle.gltf");

    Result<scene::SceneData> scene = scene::loadScene(work / "triangle.gltf");
    if (!scene) {
        return fail(scene.error().message);
    }
    Result<gpu::Context> context = gpu::Context::create();
    if (!context) {
        return fail(context.error().message);
    }
    render::RendererOptions options;
    options.target.width = 64;
    options.target.height = 64;
    Result<render::Renderer> renderer = render::Renderer::create(*context, options);
    if (!renderer) {
        return fail(renderer.error().message);
    }
    if (Result<void> prepared = renderer->prepare(*scene, render::StrategyKind::Bundles);
        !prepared) {
        return fail(prepared.error().message);
    }
    renderer->renderFrame(render::Camera::framing(scene->bounds, 1.0f));
    Result<image::ImageRgba8> image = renderer->readImage();
    if (!image) {
        return fail(image.error().message);
    }
    if (Result<std::vector<std::uint8_t>> png = image::encodePng(*image)) {
        std::ofstream(work / "triangle.png", std::ios::binary)
            .write(reinterpret_cast<const char*>(png->data()), std::streamsize(png->size()));
    }

    const std::uint8_t* centre = image->pixel(32, 32);
    const std::uint8_t* corner = image->pixel(0, 0);
    std::printf("encore_consumer: centre (%d, %d, %d), corner (%d, %d, %d) on %s\n", centre[0],
                centre[1], centre[2], corner[0], corner[1], corner[2],
                context->adapterDescription().summary().c_str());
    // The triangle is red: its red channel stands well above its green one, which the neutral
    // grey background's does not.
    if (centre[0] < centre[1] + 40 || corner[0] > corner[1] + 10) {
        return fail("the triangle is missing from the centre of the image (see triangle.png)");
    }
    return 0;
}
