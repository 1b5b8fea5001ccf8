#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "GpuTestSupport.h"
#include "gpu/Readback.h"
#include "render/BindGroupLayouts.h"
#include "render/MaterialResources.h"

namespace encore::render {
namespace {

using test::Rgba;

// A width x height image whose left half is `left` and right half `right`.
scene::Image splitImage(const std::string& name,
                        std::uint32_t width,
                        std::uint32_t height,
                        Rgba left,
                        Rgba right) {
    scene::Image image;
    image.name = name;
    image.width = width;
    image.height = height;
    for (std::uint32_t y = 0; y < height; ++y) {
        for (std::uint32_t x = 0; x < width; ++x) {
            const Rgba& color = x < width / 2 ? left : right;
            image.rgba8.insert(image.rgba8.end(), color.begin(), color.end());
        }
    }
    return image;
}

scene::Image solidImage(const std::string& name, std::uint32_t width, std::uint32_t height) {
    return splitImage(name, width, height, {10, 20, 30, 255}, {10, 20, 30, 255});
}

// Adds a texture of `image` with `sampler` (or the first sampler) and returns a reference.
scene::TextureRef addTexture(scene::SceneData& scene,
                             std::uint32_t image,
                             std::uint32_t sampler = 0) {
    if (scene.samplers.empty()) {
        scene.samplers.emplace_back();
    }
    scene.textures.push_back({scene::ImageId{image}, scene::SamplerId{sampler}});
    return scene::TextureRef{scene::TextureId{scene.textures.size() - 1}};
}

// What every test needs besides the context.
struct Fixture {
    explicit Fixture(gpu::Context& context)
        : shaders(context.device()), layouts(BindGroupLayouts::create(context.device())) {}

    // Uploads every texture slot, so the tests see linear-space textures too.
    Result<MaterialResources> create(gpu::Context& context,
                                     const scene::SceneData& scene,
                                     const SampledTextures& sampled = SampledTextures::all()) {
        return MaterialResources::create(context.device(), context.queue(), shaders, layouts, scene,
                                         sampled);
    }

    shaders::ShaderLibrary shaders;
    BindGroupLayouts layouts;
};

TEST(MaterialResourcesTest, MipChainOfSrgbTextureAveragesInLinearSpace) {
    ENCORE_REQUIRE_VULKAN(context);
    scene::SceneData scene;
    scene.images.push_back(splitImage("red|blue", 4, 4, {255, 0, 0, 255}, {0, 0, 255, 255}));
    scene.images.push_back(solidImage("wide", 8, 2));
    scene::Material split;
    split.baseColorTexture = addTexture(scene, 0);
    // The same image as non-colour data: its average is taken on the stored values.
    split.metallicRoughnessTexture = addTexture(scene, 0);
    scene.materials.push_back(split);
    scene::Material wide;
    wide.baseColorTexture = addTexture(scene, 1);
    scene.materials.push_back(wide);

    Fixture fixture(*context);
    auto resources = fixture.create(*context, scene);
    ASSERT_TRUE(resources.ok()) << resources.error().message;
    EXPECT_EQ(resources->textureCount(), 4u);  // Default, red|blue twice, wide.

    const wgpu::Texture* srgb = resources->texture(scene::ImageId{0u}, ColorSpace::Srgb);
    ASSERT_NE(srgb, nullptr);
    EXPECT_EQ(srgb->GetMipLevelCount(), 3u);

    auto level1 = gpu::readTextureLevel(*context, *srgb, 1);
    ASSERT_TRUE(level1.ok()) << level1.error().message;
    ASSERT_EQ(level1->width, 2u);
    ASSERT_EQ(level1->height, 2u);
    EXPECT_LE(test::channelDistance(test::pixelAt(*level1, 0, 1), {255, 0, 0, 255}), 1);
    EXPECT_LE(test::channelDistance(test::pixelAt(*level1, 1, 0), {0, 0, 255, 255}), 1);

    // Half red and half blue in linear light: 0.5 of each, i.e. 188 once sRGB-encoded. 128
    // would mean the encoded values were averaged.
    auto level2 = gpu::readTextureLevel(*context, *srgb, 2);
    ASSERT_TRUE(level2.ok()) << level2.error().message;
    ASSERT_EQ(level2->width, 1u);
    const std::uint8_t half = test::linearToSrgb8(0.5);
    EXPECT_EQ(half, 188);
    const Rgba average = test::pixelAt(*level2, 0, 0);
    EXPECT_LE(test::channelDistance(average, {half, 0, half, 255}), 2) << test::describe(average);

    const wgpu::Texture* linear = resources->texture(scene::ImageId{0u}, ColorSpace::Linear);
    ASSERT_NE(linear, nullptr);
    EXPECT_EQ(linear->GetFormat(), wgpu::TextureFormat::RGBA8Unorm);
    auto linearLevel2 = gpu::readTextureLevel(*context, *linear, 2);
    ASSERT_TRUE(linearLevel2.ok()) << linearLevel2.error().message;
    const Rgba linearAverage = test::pixelAt(*linearLevel2, 0, 0);
    EXPECT_LE(test::channelDistance(linearAverage, {128, 0, 128, 255}), 1)
        << test::describe(linearAverage);

    const wgpu::Texture* wideTexture = resources->texture(scene::ImageId{1u}, ColorSpace::Srgb);
    ASSERT_NE(wideTexture, nullptr);
    EXPECT_EQ(wideTexture->GetMipLevelCount(), 4u);
    auto wideLast = gpu::readTextureLevel(*context, *wideTexture, 3);
    ASSERT_TRUE(wideLast.ok()) << wideLast.error().message;
    EXPECT_EQ(wideLast->width, 1u);
    EXPECT_EQ(wideLast->height, 1u);
    EXPECT_LE(test::channelDistance(test::pixelAt(*wideLast, 0, 0), {10, 20, 30, 255}), 1);
    EXPECT_FALSE(gpu::readTextureLevel(*context, *wideTexture, 4).ok());
    EXPECT_TRUE(context->checkNoErrors("mip chain").ok());
}

TEST(MaterialResourcesTest, ColourSpaceFollowsTheTextureUse) {
    ENCORE_REQUIRE_VULKAN(context);
    scene::SceneData scene;
    for (const char* name : {"base", "metal-rough", "normal", "emissive", "unused"}) {
        scene.images.push_back(solidImage(name, 2, 2));
    }
    scene::Material material;
    material.baseColorTexture = addTexture(scene, 0);
    material.metallicRoughnessTexture = addTexture(scene, 1);
    material.normalTexture = addTexture(scene, 2);
    material.emissiveTexture = addTexture(scene, 3);
    scene.materials.push_back(material);

    Fixture fixture(*context);
    auto resources = fixture.create(*context, scene);
    ASSERT_TRUE(resources.ok()) << resources.error().message;
    EXPECT_EQ(resources->textureCount(), 5u);  // Default + four; the unused image gets none.
    auto format = [&](std::uint32_t image, ColorSpace space) {
        const wgpu::Texture* texture = resources->texture(scene::ImageId{image}, space);
        return texture ? texture->GetFormat() : wgpu::TextureFormat::Undefined;
    };
    EXPECT_EQ(format(0, ColorSpace::Srgb), wgpu::TextureFormat::RGBA8UnormSrgb);
    EXPECT_EQ(format(1, ColorSpace::Linear), wgpu::TextureFormat::RGBA8Unorm);
    EXPECT_EQ(format(2, ColorSpace::Linear), wgpu::TextureFormat::RGBA8Unorm);
    EXPECT_EQ(format(3, ColorSpace::Srgb), wgpu::TextureFormat::RGBA8UnormSrgb);
    EXPECT_EQ(format(0, ColorSpace::Linear), wgpu::TextureFormat::Undefined);
    EXPECT_EQ(format(1, ColorSpace::Srgb), wgpu::TextureFormat::Undefined);
    EXPECT_EQ(format(4, ColorSpace::Srgb), wgpu::TextureFormat::Undefined);
    EXPECT_EQ(resources->defaultBaseColorTexture().GetFormat(),
              wgpu::TextureFormat::RGBA8UnormSrgb);
    EXPECT_FALSE(resources->usesDefaultBaseColor(scene::MaterialId{0u}));
    EXPECT_TRUE(context->checkNoErrors("colour spaces").ok());
}

TEST(MaterialResourcesTest, MissingImageBindsTheWhiteDefault) {
    ENCORE_REQUIRE_VULKAN(context);
    scene::SceneData scene;
    scene::Image missing;
    missing.name = "missing.png";  // Not decodable: the loader leaves rgba8 empty.
    scene.images.push_back(missing);
    scene.images.push_back(solidImage("present", 2, 2));
    scene::Material broken;
    broken.baseColorTexture = addTexture(scene, 0);
    scene.materials.push_back(broken);
    scene.materials.push_back(scene::Material{});  // No texture at all.
    scene::Material textured;
    textured.baseColorTexture = addTexture(scene, 1);
    scene.materials.push_back(textured);

    Fixture fixture(*context);
    auto resources = fixture.create(*context, scene);
    ASSERT_TRUE(resources.ok()) << resources.error().message;
    EXPECT_EQ(resources->textureCount(), 2u);
    EXPECT_EQ(resources->texture(scene::ImageId{0u}, ColorSpace::Srgb), nullptr);
    EXPECT_TRUE(resources->usesDefaultBaseColor(scene::MaterialId{0u}));
    EXPECT_TRUE(resources->usesDefaultBaseColor(scene::MaterialId{1u}));
    EXPECT_FALSE(resources->usesDefaultBaseColor(scene::MaterialId{2u}));
    for (std::uint32_t i = 0; i < 3; ++i) {
        EXPECT_NE(resources->bindGroup(scene::MaterialId{i}).Get(), nullptr);
    }
    auto white = gpu::readTexture(*context, resources->defaultBaseColorTexture());
    ASSERT_TRUE(white.ok()) << white.error().message;
    ASSERT_EQ(white->width, 1u);
    EXPECT_EQ(test::pixelAt(*white, 0, 0), (Rgba{255, 255, 255, 255}));
    EXPECT_TRUE(context->checkNoErrors("missing image").ok());
}

// A textured material whose shading needs none of the extensions binds only the base slots to
// its own pipelines (fewer textures for Dawn to track per pass); the full group stays for
// pipelines compiled with every extension. A material that becomes textured gets both.
TEST(MaterialResourcesTest, MaterialsWithoutExtensionsDrawWithTheBaseSlots) {
    ENCORE_REQUIRE_VULKAN(context);
    scene::SceneData scene;
    scene.images.push_back(solidImage("base", 2, 2));
    scene.materials.push_back(scene::Material{});  // No texture.
    scene::Material textured;
    textured.baseColorTexture = addTexture(scene, 0);
    scene.materials.push_back(textured);
    scene::Material iridescent = textured;
    iridescent.iridescence = scene::IridescenceExtension{};
    iridescent.iridescence->iridescenceFactor = 1.0f;
    scene.materials.push_back(iridescent);

    Fixture fixture(*context);
    auto resources = fixture.create(*context, scene);
    ASSERT_TRUE(resources.ok()) << resources.error().message;
    const auto same = [&](std::uint32_t material) {
        const scene::MaterialId id{material};
        EXPECT_NE(resources->bindGroup(id).Get(), nullptr);
        EXPECT_NE(resources->drawBindGroup(id).Get(), nullptr);
        return resources->bindGroup(id).Get() == resources->drawBindGroup(id).Get();
    };
    EXPECT_TRUE(same(0));
    EXPECT_FALSE(same(1));
    EXPECT_TRUE(same(2));
    ASSERT_TRUE(resources
                    ->replaceBaseColorImage(context->device(), context->queue(), fixture.shaders,
                                            fixture.layouts, scene::MaterialId{0u},
                                            solidImage("replacement", 2, 2))
                    .ok());
    EXPECT_FALSE(same(0));
    EXPECT_TRUE(context->checkNoErrors("base slots").ok());
}

TEST(MaterialResourcesTest, EqualSamplerStatesShareOneSampler) {
    ENCORE_REQUIRE_VULKAN(context);
    scene::SceneData scene;
    scene::Sampler clampNearest;
    clampNearest.magFilter = scene::Filter::Nearest;
    clampNearest.wrapS = scene::Wrap::ClampToEdge;
    scene::Sampler mirrored;
    mirrored.wrapT = scene::Wrap::MirroredRepeat;
    scene::Sampler mirroredNoMips = mirrored;
    mirroredNoMips.useMipmaps = false;
    scene.samplers = {clampNearest, clampNearest, mirrored, mirroredNoMips, scene::Sampler{}};

    Fixture fixture(*context);
    auto resources = fixture.create(*context, scene);
    ASSERT_TRUE(resources.ok()) << resources.error().message;
    // The default, clampNearest (twice), mirrored, mirroredNoMips; the last scene sampler has
    // the default state and shares the default.
    EXPECT_EQ(resources->samplerCount(), 4u);
    auto sampler = [&](std::uint32_t id) { return resources->sampler(scene::SamplerId{id}).Get(); };
    EXPECT_EQ(sampler(0), sampler(1));
    EXPECT_NE(sampler(0), sampler(2));
    EXPECT_NE(sampler(2), sampler(3));
    EXPECT_NE(sampler(4), sampler(0));
    EXPECT_TRUE(context->checkNoErrors("samplers").ok());
}

// Reads material `index`'s MaterialUniform back from the GPU.
MaterialUniform readUniform(gpu::Context& context,
                            const MaterialResources& resources,
                            std::uint32_t index) {
    MaterialUniform uniform{};
    auto bytes = gpu::readBuffer(context, resources.uniformBuffer(),
                                 index * resources.uniformStride(), sizeof(MaterialUniform));
    EXPECT_TRUE(bytes.ok()) << bytes.error().message;
    if (bytes) {
        std::memcpy(&uniform, bytes->data(), sizeof(uniform));
    }
    return uniform;
}

void expectRow(const float (&row)[4], float a, float b, float c, const char* what) {
    EXPECT_NEAR(row[0], a, 1e-6f) << what;
    EXPECT_NEAR(row[1], b, 1e-6f) << what;
    EXPECT_NEAR(row[2], c, 1e-6f) << what;
    EXPECT_EQ(row[3], 0.0f) << what;
}

TEST(MaterialResourcesTest, UniformsHoldFactorsTransformAndCutoff) {
    ENCORE_REQUIRE_VULKAN(context);
    scene::SceneData scene;
    scene.images.push_back(solidImage("base", 2, 2));
    scene::Material transformed;
    transformed.baseColorFactor = {0.25f, 0.5f, 0.75f, 1.0f};
    transformed.baseColorTexture = addTexture(scene, 0);
    transformed.baseColorTexture->transform =
        scene::TextureTransform{{0.5f, 0.0f}, std::numbers::pi_v<float> / 2.0f, {2.0f, 2.0f}};
    transformed.alphaMode = scene::AlphaMode::Mask;
    transformed.alphaCutoff = 0.0f;
    scene.materials.push_back(transformed);
    scene::Material masked;
    masked.alphaMode = scene::AlphaMode::Mask;
    masked.alphaCutoff = 0.3f;
    scene.materials.push_back(masked);
    scene::Material opaque;  // alphaCutoff 0.5 by default, unused when opaque.
    scene.materials.push_back(opaque);

    Fixture fixture(*context);
    auto resources = fixture.create(*context, scene);
    ASSERT_TRUE(resources.ok()) << resources.error().message;
    EXPECT_EQ(resources->uniformStride() % 256, 0u);

    const MaterialUniform first = readUniform(*context, *resources, 0);
    EXPECT_EQ(first.baseColorFactor[0], 0.25f);
    EXPECT_EQ(first.baseColorFactor[1], 0.5f);
    EXPECT_EQ(first.baseColorFactor[2], 0.75f);
    EXPECT_EQ(first.baseColorFactor[3], 1.0f);
    // T(0.5, 0) * R(pi/2) * S(2, 2) with KHR_texture_transform's R = [cos sin; -sin cos]:
    // u' = 2v + 0.5, v' = -2u.
    expectRow(first.slots[0].row0, 0.0f, 2.0f, 0.5f, "row 0");
    expectRow(first.slots[0].row1, -2.0f, 0.0f, 0.0f, "row 1");
    EXPECT_EQ(first.alpha[0], 0.0f);

    const MaterialUniform second = readUniform(*context, *resources, 1);
    expectRow(second.slots[0].row0, 1.0f, 0.0f, 0.0f, "identity row 0");
    expectRow(second.slots[0].row1, 0.0f, 1.0f, 0.0f, "identity row 1");
    EXPECT_FLOAT_EQ(second.alpha[0], 0.3f);
    EXPECT_EQ(readUniform(*context, *resources, 2).alpha[0], 0.0f);

    masked.baseColorFactor = {1.0f, 0.0f, 0.0f, 0.5f};
    masked.alphaCutoff = 0.7f;
    resources->updateMaterial(context->queue(), scene::MaterialId{1u}, masked);
    const MaterialUniform updated = readUniform(*context, *resources, 1);
    EXPECT_EQ(updated.baseColorFactor[0], 1.0f);
    EXPECT_EQ(updated.baseColorFactor[1], 0.0f);
    EXPECT_EQ(updated.baseColorFactor[3], 0.5f);
    EXPECT_FLOAT_EQ(updated.alpha[0], 0.7f);
    // The neighbours are untouched.
    EXPECT_EQ(readUniform(*context, *resources, 0).baseColorFactor[0], 0.25f);
    EXPECT_EQ(readUniform(*context, *resources, 2).baseColorFactor[0], 1.0f);
    EXPECT_TRUE(context->checkNoErrors("uniforms").ok());
}

// The uniform's last flag word names the slots bound to a texture of their own: the shaders
// skip sampling the others (they would read the white default). A missing image binds the
// default and is not named; a replaced base colour image is.
TEST(MaterialResourcesTest, UniformsNameTheSlotsBoundToATexture) {
    ENCORE_REQUIRE_VULKAN(context);
    scene::SceneData scene;
    scene::Image missing;
    missing.name = "missing.png";
    scene.images.push_back(missing);
    scene.images.push_back(solidImage("present", 2, 2));
    scene::Material broken;
    broken.baseColorTexture = addTexture(scene, 0);
    scene.materials.push_back(broken);
    scene.materials.push_back(scene::Material{});
    scene::Material textured;
    textured.baseColorTexture = addTexture(scene, 1);
    textured.emissiveTexture = addTexture(scene, 1);
    scene.materials.push_back(textured);

    Fixture fixture(*context);
    auto resources = fixture.create(*context, scene);
    ASSERT_TRUE(resources.ok()) << resources.error().message;
    constexpr std::uint32_t kBaseColor = 1u << std::uint32_t(TextureSlot::BaseColor);
    constexpr std::uint32_t kEmissive = 1u << std::uint32_t(TextureSlot::Emissive);
    EXPECT_EQ(readUniform(*context, *resources, 0).flags[3], 0u);
    EXPECT_EQ(readUniform(*context, *resources, 1).flags[3], 0u);
    EXPECT_EQ(readUniform(*context, *resources, 2).flags[3], kBaseColor | kEmissive);
    // One sampler state: no slot samples through another palette entry.
    EXPECT_FALSE(resources->samplesThroughPalette(scene::MaterialId{2u}));

    ASSERT_TRUE(resources
                    ->replaceBaseColorImage(context->device(), context->queue(), fixture.shaders,
                                            fixture.layouts, scene::MaterialId{1u},
                                            solidImage("replacement", 2, 2))
                    .ok());
    EXPECT_EQ(readUniform(*context, *resources, 1).flags[3], kBaseColor);
    // A material edit keeps the word.
    resources->updateMaterial(context->queue(), scene::MaterialId{2u}, textured);
    EXPECT_EQ(readUniform(*context, *resources, 2).flags[3], kBaseColor | kEmissive);
    EXPECT_TRUE(context->checkNoErrors("slot bits").ok());
}

// Images beyond the device's maxTextureDimension2D are downscaled (DeviceLimitsTest checks the
// warning and the pixels); inconsistent ones and dangling references are errors.
TEST(MaterialResourcesTest, InconsistentImagesAreErrorsNamingTheImage) {
    ENCORE_REQUIRE_VULKAN(context);
    Fixture fixture(*context);

    scene::SceneData huge;
    huge.images.push_back(solidImage("huge.png", 4, 4));
    scene::Material material;
    material.baseColorTexture = addTexture(huge, 0);
    huge.materials.push_back(material);

    scene::SceneData truncated = huge;
    truncated.images[0] = solidImage("short.png", 4, 4);
    truncated.images[0].rgba8.resize(10);
    auto inconsistent = fixture.create(*context, truncated);
    ASSERT_FALSE(inconsistent.ok());
    EXPECT_NE(inconsistent.error().message.find("short.png"), std::string::npos)
        << inconsistent.error().message;

    scene::SceneData dangling = truncated;
    dangling.materials[0].baseColorTexture->texture = scene::TextureId{7u};
    auto badReference = fixture.create(*context, dangling);
    ASSERT_FALSE(badReference.ok());
    EXPECT_NE(badReference.error().message.find("texture 7"), std::string::npos)
        << badReference.error().message;
    EXPECT_TRUE(context->checkNoErrors("invalid images").ok());
}

}  // namespace
}  // namespace encore::render

namespace encore::render {
namespace {

// Every slot a material uses is uploaded in its colour space by default (the shading samples
// them all); a caller that samples fewer uploads only those, and the other references are still
// checked, so a dangling one is an error, not a silently skipped texture.
TEST(MaterialResourcesTest, SampledSlotsAreUploadedInTheirColourSpace) {
    ENCORE_REQUIRE_VULKAN(context);
    scene::SceneData scene;
    for (const char* name : {"base", "metal-rough", "normal", "emissive"}) {
        scene::Image image;
        image.name = name;
        image.width = image.height = 2;
        image.rgba8.assign(16, 200);
        scene.images.push_back(image);
    }
    scene.samplers.push_back({});
    for (std::uint32_t i = 0; i < 4; ++i) {
        scene.textures.push_back({scene::ImageId{i}, scene::SamplerId{0u}});
    }
    scene::Material material;
    material.baseColorTexture = scene::TextureRef{scene::TextureId{0u}};
    material.metallicRoughnessTexture = scene::TextureRef{scene::TextureId{1u}};
    material.normalTexture = scene::TextureRef{scene::TextureId{2u}};
    material.emissiveTexture = scene::TextureRef{scene::TextureId{3u}};
    scene.materials.push_back(material);

    shaders::ShaderLibrary shaders(context->device());
    const BindGroupLayouts layouts = BindGroupLayouts::create(context->device());
    auto all =
        MaterialResources::create(context->device(), context->queue(), shaders, layouts, scene);
    ASSERT_TRUE(all.ok()) << all.error().message;
    EXPECT_EQ(all->textureCount(), 5u);  // The white default and the four images.
    EXPECT_NE(all->texture(scene::ImageId{0u}, ColorSpace::Srgb), nullptr);
    EXPECT_NE(all->texture(scene::ImageId{1u}, ColorSpace::Linear), nullptr);
    EXPECT_NE(all->texture(scene::ImageId{2u}, ColorSpace::Linear), nullptr);
    EXPECT_NE(all->texture(scene::ImageId{3u}, ColorSpace::Srgb), nullptr);
    EXPECT_EQ(all->texture(scene::ImageId{2u}, ColorSpace::Srgb), nullptr);

    auto resources = MaterialResources::create(context->device(), context->queue(), shaders,
                                               layouts, scene, SampledTextures::baseColorOnly());
    ASSERT_TRUE(resources.ok()) << resources.error().message;
    EXPECT_EQ(resources->textureCount(), 2u);  // The white default and the base colour.
    EXPECT_NE(resources->texture(scene::ImageId{0u}, ColorSpace::Srgb), nullptr);
    EXPECT_EQ(resources->texture(scene::ImageId{2u}, ColorSpace::Linear), nullptr);

    scene.materials[0].normalTexture = scene::TextureRef{scene::TextureId{9u}};
    auto dangling = MaterialResources::create(context->device(), context->queue(), shaders, layouts,
                                              scene, SampledTextures::baseColorOnly());
    ASSERT_FALSE(dangling.ok());
    EXPECT_NE(dangling.error().message.find("texture 9"), std::string::npos)
        << dangling.error().message;
    EXPECT_TRUE(context->checkNoErrors("sampled slots").ok());
}

}  // namespace
}  // namespace encore::render
