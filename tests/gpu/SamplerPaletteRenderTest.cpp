// A material binds a palette of four samplers that its texture slots share (SamplerPalette.h):
// each slot samples with its own glTF sampler while the material has at most four distinct
// ones, and a slot past them samples with the nearest, with a warning. Checked in the pixels of
// the fragment path (`materials`) and of the compute resolve (`visibility`).

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "GltfBuilder.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "core/Log.h"
#include "encore/render/Renderer.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSize = 64;
const glm::vec3 kFacing(0.0f, 0.0f, 1.0f);
constexpr float kHalfWidth = 2.5f;

// glTF sampler constants.
constexpr int kNearest = 9728;
constexpr int kLinear = 9729;
constexpr int kRepeat = 10497;
constexpr int kClamp = 33071;
constexpr int kMirror = 33648;

class WarningCapture {
  public:
    WarningCapture() {
        mPrevious = setLogSink([this](LogLevel level, std::string_view message) {
            if (level == LogLevel::Warning) {
                warnings.emplace_back(message);
            }
        });
    }
    ~WarningCapture() { setLogSink(mPrevious); }
    std::vector<std::string> warnings;

  private:
    LogSink mPrevious;
};

// A quad facing the camera whose TEXCOORD_0 runs from 0 to 2 left to right (and 0 to 1 top to
// bottom), so the sampler's wrap mode decides what its right half shows.
std::uint32_t addWideQuad(test::GltfBuilder& builder, std::uint32_t material) {
    test::GltfBuilder::PrimitiveDesc primitive;
    const float w = kHalfWidth;
    primitive.attributes["POSITION"] =
        builder.addPositions({{-w, -1, 0}, {w, -1, 0}, {w, 1, 0}, {-w, 1, 0}});
    primitive.attributes["NORMAL"] = builder.addNormals({kFacing, kFacing, kFacing, kFacing});
    primitive.attributes["TEXCOORD_0"] = builder.addTexcoords({{0, 1}, {2, 1}, {2, 0}, {0, 0}});
    primitive.indices = builder.addIndices<std::uint16_t>({0, 1, 2, 0, 2, 3});
    primitive.material = material;
    return builder.addNode({.mesh = builder.addMesh(primitive)});
}

// A 2x1 image, red then blue, and one texture of it per sampler state given.
std::vector<std::uint32_t> addRedBlueTextures(test::GltfBuilder& builder,
                                              const std::vector<nlohmann::json>& samplers) {
    image::ImageRgba8 pixels{2, 1, {255, 0, 0, 255, 0, 0, 255, 255}};
    const auto png = image::encodePng(pixels);
    EXPECT_TRUE(png.ok());
    auto& json = builder.json();
    json["images"].push_back(
        {{"bufferView", builder.addBufferView(*png)}, {"mimeType", "image/png"}});
    std::vector<std::uint32_t> textures;
    for (const nlohmann::json& sampler : samplers) {
        json["samplers"].push_back(sampler);
        json["textures"].push_back(
            {{"source", json["images"].size() - 1}, {"sampler", json["samplers"].size() - 1}});
        textures.push_back(std::uint32_t(json["textures"].size() - 1));
    }
    return textures;
}

nlohmann::json sampler(int wrapS, int magFilter, int minFilter) {
    return {
        {"wrapS", wrapS}, {"wrapT", kRepeat}, {"magFilter", magFilter}, {"minFilter", minFilter}};
}

// The emissive channel of a quad whose emissive texture (the fifth slot) has a fifth distinct
// sampler: mirrored repeat, nearest. Entry 0 of the palette repeats and would show red where the
// mirror shows blue; the nearest entry (mirrored repeat, nearest magnification, linear
// minification, which a magnified texture does not use) draws it as its own would.
class SamplerPaletteRenderTest : public ::testing::TestWithParam<StrategyKind> {};

TEST_P(SamplerPaletteRenderTest, ASlotPastThePaletteSamplesWithTheNearestSampler) {
    ENCORE_REQUIRE_VULKAN(context);
    test::GltfBuilder builder;
    const std::vector<std::uint32_t> textures =
        addRedBlueTextures(builder, {
                                        sampler(kRepeat, kNearest, kNearest),  // Base colour.
                                        sampler(kClamp, kNearest, kNearest),   // Metal-rough.
                                        sampler(kMirror, kLinear, kLinear),    // Normal.
                                        sampler(kMirror, kNearest, kLinear),   // Occlusion.
                                        sampler(kMirror, kNearest, kNearest),  // Emissive.
                                    });
    builder.json()["materials"].push_back({
        {"name", "five samplers"},
        {"pbrMetallicRoughness",
         {{"baseColorTexture", {{"index", textures[0]}}},
          {"metallicRoughnessTexture", {{"index", textures[1]}}}}},
        {"normalTexture", {{"index", textures[2]}}},
        {"occlusionTexture", {{"index", textures[3]}}},
        {"emissiveTexture", {{"index", textures[4]}}},
        {"emissiveFactor", {1.0, 1.0, 1.0}},
    });
    builder.addScene({addWideQuad(builder, 0)});
    auto scene = scene::loadSceneFromMemory(builder.toGlb(), {}, "palette.glb");
    ASSERT_TRUE(scene.ok()) << scene.error().message;

    auto renderer =
        Renderer::create(*context, test::pixelTestOptions(kSize, kSize, 1, DebugChannel::Emissive));
    ASSERT_TRUE(renderer.ok()) << renderer.error().message;
    WarningCapture capture;
    ASSERT_TRUE(renderer->prepare(*scene, GetParam()).ok());
    renderer->renderFrame(test::frontCamera());
    auto image = renderer->readImage();
    ASSERT_TRUE(image.ok()) << image.error().message;
    EXPECT_TRUE(context->checkNoErrors("palette").ok());

    ASSERT_EQ(capture.warnings.size(), 1u);
    EXPECT_EQ(capture.warnings[0],
              "Material 0 ('five samplers')'s textures use more distinct samplers than the 4 a "
              "material binds; the nearest stand in: emissiveTexture (sampler 4) samples with "
              "sampler 3.");

    const test::Rgba red{255, 0, 0, 255};
    const test::Rgba blue{0, 0, 255, 255};
    // u = 0.25, 0.75, 1.25 and 1.75 across the quad; mirrored, u = 1.25 reads 0.75 and 1.75
    // reads 0.25.
    const std::vector<std::pair<float, test::Rgba>> expected = {
        {0.25f, red}, {0.75f, blue}, {1.25f, blue}, {1.75f, red}};
    for (const auto& [u, colour] : expected) {
        const glm::vec3 point(-kHalfWidth + kHalfWidth * u, 0.0f, 0.0f);
        const auto [x, y] = test::pixelOf(test::frontCamera(), point, kSize, kSize);
        const test::Rgba actual = test::pixelAt(*image, x, y);
        EXPECT_LE(test::channelDistance(actual, colour), 1)
            << "u = " << u << " at (" << x << ", " << y << "): " << test::describe(actual)
            << ", expected " << test::describe(colour);
    }
}

INSTANTIATE_TEST_SUITE_P(Strategies,
                         SamplerPaletteRenderTest,
                         ::testing::Values(StrategyKind::Materials, StrategyKind::Visibility),
                         [](const auto& info) { return test::strategyTestName(info.param); });

}  // namespace
}  // namespace encore::render
