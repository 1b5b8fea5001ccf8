#include "VariantFixture.h"

#include "TextureFixtures.h"

namespace encore::test {
namespace {

std::uint32_t addQuad(GltfBuilder& builder, float left, float right) {
    const glm::vec3 facing(0.0f, 0.0f, 1.0f);
    GltfBuilder::PrimitiveDesc primitive;
    primitive.attributes["POSITION"] =
        builder.addPositions({{left, -1, 0}, {right, -1, 0}, {right, 1, 0}, {left, 1, 0}});
    primitive.attributes["NORMAL"] = builder.addNormals({facing, facing, facing, facing});
    primitive.attributes["TEXCOORD_0"] = builder.addTexcoords({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
    primitive.attributes["TANGENT"] = builder.addAccessor(
        std::vector<float>{1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1}, "VEC4");
    primitive.indices = builder.addIndices<std::uint16_t>({0, 1, 2, 0, 2, 3});
    return builder.addMesh(primitive);  // Only its primitive is used.
}

std::uint32_t addPngTexture(GltfBuilder& builder, std::array<std::uint8_t, 4> rgba) {
    const auto png = encodePngBytes(solidImage(rgba));
    const std::uint32_t image = addEmbeddedImage(builder, png, "image/png");
    auto& textures = builder.json()["textures"];
    textures.push_back({{"source", image}});
    return static_cast<std::uint32_t>(textures.size() - 1);
}

}  // namespace

GltfBuilder variantQuads() {
    GltfBuilder builder;
    auto material = [&](glm::vec3 color, const std::string& alphaMode = "OPAQUE") {
        return builder.addMaterial(
            {.baseColor = glm::vec4(color, 1.0f), .alphaMode = alphaMode, .doubleSided = true});
    };
    const std::uint32_t red = material(kLeftQuadColors[0]);
    const std::uint32_t green = material(kLeftQuadColors[1]);
    const std::uint32_t blue = material(kLeftQuadColors[2]);
    const std::uint32_t glass = material(kLeftQuadColors[3], "BLEND");
    const std::uint32_t textured = material(glm::vec3(1.0f));
    const std::uint32_t grey = material(kRightQuadColor);
    auto& json = builder.json();
    json["materials"][textured]["pbrMetallicRoughness"]["baseColorTexture"] = {
        {"index", addPngTexture(builder, {255, 0, 255, 255})}};
    json["materials"][textured]["normalTexture"] = {
        {"index", addPngTexture(builder, {128, 128, 255, 255})}};

    // One mesh of two primitives: the quads' own meshes lend theirs.
    const std::uint32_t leftMesh = addQuad(builder, -2.0f, -0.2f);
    const std::uint32_t rightMesh = addQuad(builder, 0.2f, 2.0f);
    nlohmann::json left = json["meshes"][leftMesh]["primitives"][0];
    nlohmann::json right = json["meshes"][rightMesh]["primitives"][0];
    left["material"] = red;
    right["material"] = grey;
    left["extensions"]["KHR_materials_variants"]["mappings"] = {
        {{"material", green}, {"variants", {0}}},
        {{"material", blue}, {"variants", {1}}},
        {{"material", glass}, {"variants", {2}}},
        {{"material", textured}, {"variants", {3}}, {"name", "magenta"}},
    };
    json["meshes"] = nlohmann::json::array({{{"primitives", {left, right}}}});
    builder.addScene({builder.addNode({.mesh = 0u})});

    nlohmann::json variants = nlohmann::json::array();
    for (const char* name : kVariantNames) {
        variants.push_back({{"name", name}});
    }
    json["extensions"]["KHR_materials_variants"]["variants"] = variants;
    json["extensionsUsed"] = {"KHR_materials_variants"};
    return builder;
}

}  // namespace encore::test
