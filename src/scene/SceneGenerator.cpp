#include "scene/SceneGenerator.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>

#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "scene/GlbWriter.h"

#include "encore/image/ImageCodec.h"

namespace encore::scene {

namespace {

using nlohmann::json;

struct MeshGeometry {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> texcoords;
    std::vector<std::uint32_t> indices;

    std::uint32_t addVertex(const glm::vec3& position,
                            const glm::vec3& normal,
                            const glm::vec2& texcoord) {
        positions.push_back(position);
        normals.push_back(normal);
        texcoords.push_back(texcoord);
        return static_cast<std::uint32_t>(positions.size() - 1);
    }
    void addQuad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
        indices.insert(indices.end(), {a, b, c, a, c, d});
    }
};

// A surface of revolution around Y: `profile(t)` gives (radius, height) and the outward normal
// in the (r, y) plane for t in [0, 1].
template <typename Profile>
MeshGeometry revolve(std::uint32_t segments, std::uint32_t rings, Profile profile) {
    MeshGeometry mesh;
    for (std::uint32_t ring = 0; ring <= rings; ++ring) {
        const float t = float(ring) / float(rings);
        const auto [radius, height, normalR, normalY] = profile(t);
        for (std::uint32_t segment = 0; segment <= segments; ++segment) {
            const float angle = glm::two_pi<float>() * float(segment) / float(segments);
            const float c = std::cos(angle);
            const float s = std::sin(angle);
            mesh.addVertex({radius * c, height, radius * s},
                           glm::normalize(glm::vec3(normalR * c, normalY, normalR * s)),
                           {float(segment) / float(segments), t});
        }
    }
    const std::uint32_t stride = segments + 1;
    for (std::uint32_t ring = 0; ring < rings; ++ring) {
        for (std::uint32_t segment = 0; segment < segments; ++segment) {
            const std::uint32_t a = ring * stride + segment;
            // Counter-clockwise seen from outside.
            mesh.addQuad(a, a + stride, a + stride + 1, a + 1);
        }
    }
    return mesh;
}

void addDisk(MeshGeometry& mesh, std::uint32_t segments, float radius, float height, bool up) {
    const glm::vec3 normal(0.0f, up ? 1.0f : -1.0f, 0.0f);
    const std::uint32_t center = mesh.addVertex({0.0f, height, 0.0f}, normal, {0.5f, 0.5f});
    const std::uint32_t first = static_cast<std::uint32_t>(mesh.positions.size());
    for (std::uint32_t segment = 0; segment <= segments; ++segment) {
        const float angle = glm::two_pi<float>() * float(segment) / float(segments);
        mesh.addVertex({radius * std::cos(angle), height, radius * std::sin(angle)}, normal,
                       {0.5f + 0.5f * std::cos(angle), 0.5f + 0.5f * std::sin(angle)});
    }
    for (std::uint32_t segment = 0; segment < segments; ++segment) {
        if (up) {
            mesh.indices.insert(mesh.indices.end(), {center, first + segment + 1, first + segment});
        } else {
            mesh.indices.insert(mesh.indices.end(), {center, first + segment, first + segment + 1});
        }
    }
}

MeshGeometry makeBox() {
    MeshGeometry mesh;
    for (int axis = 0; axis < 3; ++axis) {
        for (float sign : {-1.0f, 1.0f}) {
            glm::vec3 normal(0.0f);
            normal[axis] = sign;
            const glm::vec3 u = glm::vec3(normal.y, normal.z, normal.x);  // Perpendicular axes.
            const glm::vec3 v = glm::cross(normal, u);
            const std::uint32_t base = static_cast<std::uint32_t>(mesh.positions.size());
            for (int corner = 0; corner < 4; ++corner) {
                const float a = (corner == 1 || corner == 2) ? 1.0f : -1.0f;
                const float b = corner >= 2 ? 1.0f : -1.0f;
                mesh.addVertex(0.5f * (normal + a * u + b * v), normal,
                               {0.5f + 0.5f * a, 0.5f + 0.5f * b});
            }
            mesh.addQuad(base, base + 1, base + 2, base + 3);
        }
    }
    return mesh;
}

// Mesh `index`: the shape cycles, the tessellation grows, so every mesh is distinct.
MeshGeometry makeMesh(std::uint32_t index, std::uint32_t tessellation) {
    const std::uint32_t detail = tessellation + 4 * (index / 5);
    switch (index % 5) {
        case 0: {
            MeshGeometry box = makeBox();
            const float stretch = 1.0f + 0.1f * float(index / 5);
            for (auto& p : box.positions) {
                p.y *= stretch;
            }
            return box;
        }
        case 1:
            return revolve(detail * 2, detail, [](float t) {
                const float phi = glm::pi<float>() * t;
                return std::array{0.5f * std::sin(phi), -0.5f * std::cos(phi), std::sin(phi),
                                  -std::cos(phi)};
            });
        case 2: {
            auto mesh = revolve(detail * 2, 1, [](float t) {
                return std::array{0.4f, t - 0.5f, 1.0f, 0.0f};
            });
            addDisk(mesh, detail * 2, 0.4f, 0.5f, true);
            addDisk(mesh, detail * 2, 0.4f, -0.5f, false);
            return mesh;
        }
        case 3: {
            // Slant normal of a cone of radius 0.5 and height 1.
            const float length = std::sqrt(1.0f + 0.25f);
            auto mesh = revolve(detail * 2, 1, [&](float t) {
                return std::array{0.5f * (1.0f - t), t - 0.5f, 1.0f / length, 0.5f / length};
            });
            addDisk(mesh, detail * 2, 0.5f, -0.5f, false);
            return mesh;
        }
        default: {
            // A torus as rings of a tube around Y.
            MeshGeometry mesh;
            const std::uint32_t segments = detail * 2;
            const std::uint32_t sides = detail;
            for (std::uint32_t i = 0; i <= segments; ++i) {
                const float u = glm::two_pi<float>() * float(i) / float(segments);
                for (std::uint32_t j = 0; j <= sides; ++j) {
                    const float v = glm::two_pi<float>() * float(j) / float(sides);
                    const glm::vec3 center(0.35f * std::cos(u), 0.0f, 0.35f * std::sin(u));
                    const glm::vec3 normal(std::cos(v) * std::cos(u), std::sin(v),
                                           std::cos(v) * std::sin(u));
                    mesh.addVertex(center + 0.15f * normal, normal,
                                   {float(i) / float(segments), float(j) / float(sides)});
                }
            }
            for (std::uint32_t i = 0; i < segments; ++i) {
                for (std::uint32_t j = 0; j < sides; ++j) {
                    const std::uint32_t a = i * (sides + 1) + j;
                    const std::uint32_t b = a + sides + 1;
                    mesh.addQuad(a, a + 1, b + 1, b);
                }
            }
            return mesh;
        }
    }
}

glm::vec3 paletteColor(std::uint32_t index, std::uint32_t count) {
    // Evenly spaced hues at full saturation, in linear space.
    const float hue = float(index) / float(std::max(count, 1u)) * 6.0f;
    const float x = 1.0f - std::abs(std::fmod(hue, 2.0f) - 1.0f);
    glm::vec3 rgb;
    switch (int(hue) % 6) {
        case 0:
            rgb = {1, x, 0};
            break;
        case 1:
            rgb = {x, 1, 0};
            break;
        case 2:
            rgb = {0, 1, x};
            break;
        case 3:
            rgb = {0, x, 1};
            break;
        case 4:
            rgb = {x, 0, 1};
            break;
        default:
            rgb = {1, 0, x};
            break;
    }
    return 0.1f + 0.8f * rgb;
}

// [min, max] of `values`, for a POSITION accessor.
json boundsOf(const std::vector<glm::vec3>& values) {
    glm::vec3 low(INFINITY), high(-INFINITY);
    for (const auto& v : values) {
        low = glm::min(low, v);
        high = glm::max(high, v);
    }
    return {{low.x, low.y, low.z}, {high.x, high.y, high.z}};
}

constexpr std::uint32_t kTextureSize = 64;

// Eight by eight squares of white and light grey: the material's factor gives the hue.
image::ImageRgba8 checkerImage() {
    image::ImageRgba8 image{kTextureSize, kTextureSize,
                            ReusedBytes(kTextureSize * kTextureSize * 4)};
    for (std::uint32_t y = 0; y < kTextureSize; ++y) {
        for (std::uint32_t x = 0; x < kTextureSize; ++x) {
            const bool light = ((x / 8) + (y / 8)) % 2 == 0;
            std::uint8_t* p = image.pixel(x, y);
            p[0] = p[1] = p[2] = light ? 255 : 150;
            p[3] = 255;
        }
    }
    return image;
}

// glTF's metallicRoughnessTexture: blue is metalness (bands of metal and dielectric across u),
// green roughness (a ramp from 0.25 to 1 along v, times the factor).
image::ImageRgba8 metallicRoughnessImage() {
    image::ImageRgba8 image{kTextureSize, kTextureSize,
                            ReusedBytes(kTextureSize * kTextureSize * 4)};
    for (std::uint32_t y = 0; y < kTextureSize; ++y) {
        for (std::uint32_t x = 0; x < kTextureSize; ++x) {
            std::uint8_t* p = image.pixel(x, y);
            p[0] = 0;
            p[1] = std::uint8_t(64 + (191 * y) / (kTextureSize - 1));
            p[2] = (x / 16) % 2 == 0 ? 255 : 0;
            p[3] = 255;
        }
    }
    return image;
}

// Spacing in units from the options' spacing in object radii (meshes are about a unit wide).
float unitSpacing(const GeneratorOptions& options) {
    return std::max(options.spacing, 1.0f) * 0.5f;
}

json node(std::uint32_t mesh,
          const glm::vec3& translation,
          const glm::quat& rotation,
          const glm::vec3& scale) {
    return {{"mesh", mesh},
            {"translation", {translation.x, translation.y, translation.z}},
            {"rotation", {rotation.x, rotation.y, rotation.z, rotation.w}},
            {"scale", {scale.x, scale.y, scale.z}}};
}

// A seeded random turn about a random axis and a size of 0.6 to 1, drawn in this order (the
// grid's nodes have always drawn them so: its scenes stay as they were).
struct RandomPose {
    glm::quat rotation;
    float scale;
};
RandomPose randomPose(std::mt19937& random) {
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const glm::vec3 axis =
        glm::normalize(glm::vec3(unit(random), unit(random), unit(random)) + glm::vec3(0.01f));
    const glm::quat rotation = glm::angleAxis(glm::two_pi<float>() * unit(random), axis);
    const float scale = 0.6f + 0.4f * unit(random);
    return {rotation, scale};
}

// Objects on a square grid in the XZ plane, with a seeded random turn and size each.
void addGridNodes(json& document, const GeneratorOptions& options, std::mt19937& random) {
    const std::uint32_t side =
        static_cast<std::uint32_t>(std::ceil(std::sqrt(double(options.objectCount))));
    const float spacing = unitSpacing(options);
    const float origin = -0.5f * float(side - 1) * spacing;
    for (std::uint32_t i = 0; i < options.objectCount; ++i) {
        const float x = origin + float(i % side) * spacing;
        const float z = origin + float(i / side) * spacing;
        const RandomPose pose = randomPose(random);
        document["nodes"].push_back(
            node(i % options.meshCount, {x, 0.0f, z}, pose.rotation, glm::vec3(pose.scale)));
    }
}

void addLatticeNodes(json& document, const GeneratorOptions& options, std::mt19937& random) {
    const LatticeLayout lattice = latticeLayout(options);
    const std::uint32_t perLayer = lattice.side * lattice.side;
    for (std::uint32_t i = 0; i < options.objectCount; ++i) {
        const glm::vec3 point(float(i % lattice.side), float(i / perLayer),
                              float((i / lattice.side) % lattice.side));
        const RandomPose pose = randomPose(random);
        document["nodes"].push_back(node(i % options.meshCount,
                                         lattice.origin + lattice.spacing * point, pose.rotation,
                                         glm::vec3(pose.scale)));
    }
}

// makeMesh's boxes are meshes 0, 5, 10, ... stretched along Y by this factor.
float boxStretch(std::uint32_t mesh) {
    return 1.0f + 0.1f * float(mesh / 5);
}

// `meshBottoms`: the lowest Y of each mesh, so that the small objects stand on the ground.
void addCityNodes(json& document,
                  const GeneratorOptions& options,
                  std::mt19937& random,
                  const std::vector<float>& meshBottoms) {
    const CityLayout city = cityLayout(options);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const std::uint32_t boxCount = (options.meshCount + 4) / 5;
    std::vector<std::uint32_t> streetMeshes;  // Everything round; the box when there is none.
    for (std::uint32_t mesh = 0; mesh < options.meshCount; ++mesh) {
        if (mesh % 5 != 0) {
            streetMeshes.push_back(mesh);
        }
    }
    if (streetMeshes.empty()) {
        streetMeshes.push_back(0);
    }
    const float blockSize = city.blockSize();
    for (std::uint32_t i = 0; i < options.objectCount; ++i) {
        const std::uint32_t block = i / CityLayout::kObjectsPerBlock;
        const std::uint32_t slot = i % CityLayout::kObjectsPerBlock;
        // The block's south-west corner: half a street in from the streets around it.
        const glm::vec2 corner(
            city.streetCenter(int(block % city.blocksPerSide)) + 0.5f * city.streetWidth,
            city.streetCenter(int(block / city.blocksPerSide)) + 0.5f * city.streetWidth);
        constexpr std::uint32_t kLots = CityLayout::kLotsPerSide * CityLayout::kLotsPerSide;
        if (slot < kLots) {
            const glm::vec2 lot =
                corner + city.lotSize * glm::vec2(float(slot % CityLayout::kLotsPerSide) + 0.5f,
                                                  float(slot / CityLayout::kLotsPerSide) + 0.5f);
            const std::uint32_t mesh =
                5 * std::min(std::uint32_t(unit(random) * boxCount), boxCount - 1);
            // Mostly low buildings and a few towers (the square favours small heights).
            const float tower = unit(random);
            const float height = 1.5f + (city.maxBuildingHeight - 1.5f) * tower * tower;
            const glm::vec2 footprint =
                city.lotSize * glm::vec2(0.6f + 0.3f * unit(random), 0.6f + 0.3f * unit(random));
            document["nodes"].push_back(
                node(mesh, {lot.x, 0.5f * height, lot.y}, glm::quat(1.0f, 0.0f, 0.0f, 0.0f),
                     {footprint.x, height / boxStretch(mesh), footprint.y}));
            continue;
        }
        // Small objects on the pavement: beside the middle lot on the south and west sides and
        // the east lot on the south side, half way from the buildings to the street's centre
        // line (where a camera drives), and away from the crossings (where it turns).
        const float pavement = -0.25f * city.streetWidth;  // From the block's edge.
        glm::vec2 position;
        switch (slot - kLots) {
            case 0:
                position = corner + glm::vec2(1.5f * city.lotSize, pavement);
                break;
            case 1:
                position = corner + glm::vec2(pavement, 1.5f * city.lotSize);
                break;
            default:
                position = corner + glm::vec2(blockSize - 0.5f * city.lotSize, pavement);
        }
        const std::uint32_t mesh = streetMeshes[std::min(
            std::size_t(unit(random) * float(streetMeshes.size())), streetMeshes.size() - 1)];
        const float scale = 0.5f + 0.3f * unit(random);
        const glm::quat turn =
            glm::angleAxis(glm::two_pi<float>() * unit(random), glm::vec3(0.0f, 1.0f, 0.0f));
        document["nodes"].push_back(node(mesh, {position.x, -meshBottoms[mesh] * scale, position.y},
                                         turn, glm::vec3(scale)));
    }
}

}  // namespace

std::string_view sceneLayoutName(SceneLayout layout) {
    switch (layout) {
        case SceneLayout::Grid:
            return "grid";
        case SceneLayout::Lattice:
            return "lattice";
        case SceneLayout::City:
            return "city";
    }
    return "unknown";
}

LatticeLayout latticeLayout(const GeneratorOptions& options) {
    LatticeLayout lattice;
    const double objects = std::max(options.objectCount, 1u);
    lattice.layers =
        std::max(1u, static_cast<std::uint32_t>(std::lround(std::cbrt(objects / 16.0))));
    lattice.side = static_cast<std::uint32_t>(
        std::ceil(std::sqrt(std::ceil(objects / double(lattice.layers)))));
    lattice.spacing = unitSpacing(options);
    const float halfWidth = 0.5f * float(lattice.side - 1) * lattice.spacing;
    lattice.origin = {-halfWidth, 0.0f, -halfWidth};
    return lattice;
}

CityLayout cityLayout(const GeneratorOptions& options) {
    CityLayout city;
    const std::uint32_t blocks =
        (std::max(options.objectCount, 1u) + CityLayout::kObjectsPerBlock - 1) /
        CityLayout::kObjectsPerBlock;
    city.blocksPerSide = static_cast<std::uint32_t>(std::ceil(std::sqrt(double(blocks))));
    return city;
}

namespace {

Result<void> checkGeneratorOptions(const GeneratorOptions& options) {
    auto outOfRange = [](const char* what, std::uint32_t value, std::uint32_t max) {
        return makeError(ErrorCode::InvalidArgument,
                         std::string("The number of ") + what + " (" + std::to_string(value) +
                             ") must be between 1 and " + std::to_string(max) + ".");
    };
    if (options.objectCount == 0 || options.objectCount > kMaxGeneratedObjects) {
        return outOfRange("objects", options.objectCount, kMaxGeneratedObjects);
    }
    if (options.meshCount == 0 || options.meshCount > kMaxGeneratedMeshes) {
        return outOfRange("meshes", options.meshCount, kMaxGeneratedMeshes);
    }
    if (options.materialCount == 0 || options.materialCount > kMaxGeneratedMaterials) {
        return outOfRange("materials", options.materialCount, kMaxGeneratedMaterials);
    }
    if (options.tessellation < 3 || options.tessellation > 256) {
        return makeError(ErrorCode::InvalidArgument, "The tessellation (" +
                                                         std::to_string(options.tessellation) +
                                                         ") must be between 3 and 256 segments.");
    }
    return {};
}

// The checker and metallic-roughness images, their sampler and two textures.
Result<void> addTextures(json& document, GlbBinaryChunk& binary) {
    ENCORE_TRY_ASSIGN(auto checker, image::encodePng(checkerImage()));
    ENCORE_TRY_ASSIGN(auto metallicRoughness, image::encodePng(metallicRoughnessImage()));
    document["images"] = json::array();
    binary.addPng(document, checker);
    binary.addPng(document, metallicRoughness);
    constexpr int kLinear = 9729;
    constexpr int kLinearMipmapLinear = 9987;
    constexpr int kRepeat = 10497;
    document["samplers"] = {{{"magFilter", kLinear},
                             {"minFilter", kLinearMipmapLinear},
                             {"wrapS", kRepeat},
                             {"wrapT", kRepeat}}};
    document["textures"] = {{{"source", 0}, {"sampler", 0}}, {{"source", 1}, {"sampler", 0}}};
    return {};
}

void addMaterials(json& document, const GeneratorOptions& options) {
    for (std::uint32_t i = 0; i < options.materialCount; ++i) {
        const glm::vec3 color = paletteColor(i, options.materialCount);
        // Every third material (from the second) is a metal and roughness runs from 0.2 to 0.9
        // across the materials, so a render shows dielectric and metallic highlights of several
        // widths while the hues keep the materials apart.
        const bool metal = i % 3 == 1;
        const float roughness = options.materialCount > 1
                                    ? 0.2f + 0.7f * float(i) / float(options.materialCount - 1)
                                    : 0.5f;
        json material = {{"name", "material " + std::to_string(i)},
                         {"pbrMetallicRoughness",
                          {{"baseColorFactor", {color.r, color.g, color.b, 1.0}},
                           {"metallicFactor", metal ? 1.0 : 0.0},
                           {"roughnessFactor", roughness}}}};
        if (options.textures && i % 2 == 1) {
            // The texture's bands decide metalness, so the factor lets them through.
            auto& pbr = material["pbrMetallicRoughness"];
            pbr["baseColorTexture"] = {{"index", 0}};
            pbr["metallicRoughnessTexture"] = {{"index", 1}};
            pbr["metallicFactor"] = 1.0;
        }
        document["materials"].push_back(std::move(material));
    }
}

// The meshes' primitives; returns each mesh's lowest y (the city layout stands them on it).
std::vector<float> addMeshes(json& document,
                             GlbBinaryChunk& binary,
                             const GeneratorOptions& options) {
    constexpr int kFloat = 5126;
    constexpr int kUnsignedShort = 5123;
    constexpr int kUnsignedInt = 5125;
    constexpr int kArrayBuffer = 34962;
    constexpr int kElementArrayBuffer = 34963;
    std::vector<float> meshBottoms;
    for (std::uint32_t i = 0; i < options.meshCount; ++i) {
        const MeshGeometry mesh = makeMesh(i, options.tessellation);
        meshBottoms.push_back(
            std::min_element(mesh.positions.begin(), mesh.positions.end(),
                             [](const glm::vec3& a, const glm::vec3& b) { return a.y < b.y; })
                ->y);
        json attributes = {
            {"POSITION",
             binary.addAccessor(document, mesh.positions, kFloat, "VEC3", mesh.positions.size(),
                                kArrayBuffer, boundsOf(mesh.positions))},
            {"NORMAL", binary.addAccessor(document, mesh.normals, kFloat, "VEC3",
                                          mesh.normals.size(), kArrayBuffer)},
            {"TEXCOORD_0", binary.addAccessor(document, mesh.texcoords, kFloat, "VEC2",
                                              mesh.texcoords.size(), kArrayBuffer)}};
        std::size_t indices;
        if (mesh.positions.size() <= 65536) {
            std::vector<std::uint16_t> narrow(mesh.indices.begin(), mesh.indices.end());
            indices = binary.addAccessor(document, narrow, kUnsignedShort, "SCALAR", narrow.size(),
                                         kElementArrayBuffer);
        } else {
            indices = binary.addAccessor(document, mesh.indices, kUnsignedInt, "SCALAR",
                                         mesh.indices.size(), kElementArrayBuffer);
        }
        document["meshes"].push_back({{"name", "mesh " + std::to_string(i)},
                                      {"primitives",
                                       {{{"attributes", attributes},
                                         {"indices", indices},
                                         {"material", i % options.materialCount}}}}});
    }

    return meshBottoms;
}

}  // namespace

Result<std::vector<std::uint8_t>> generateSceneGlb(const GeneratorOptions& options) {
    ENCORE_TRY(checkGeneratorOptions(options));
    json document = {{"asset", {{"version", "2.0"}, {"generator", "encore gen"}}},
                     {"scene", 0},
                     {"buffers", json::array()},
                     {"bufferViews", json::array()},
                     {"accessors", json::array()},
                     {"meshes", json::array()},
                     {"materials", json::array()},
                     {"nodes", json::array()}};
    GlbBinaryChunk binary;
    if (options.textures) {
        ENCORE_TRY(addTextures(document, binary));
    }
    addMaterials(document, options);
    const std::vector<float> meshBottoms = addMeshes(document, binary, options);
    std::mt19937 random(options.seed);
    switch (options.layout) {
        case SceneLayout::Grid:
            addGridNodes(document, options, random);
            break;
        case SceneLayout::Lattice:
            addLatticeNodes(document, options, random);
            break;
        case SceneLayout::City:
            addCityNodes(document, options, random, meshBottoms);
            break;
    }
    json rootChildren = json::array();
    for (std::uint32_t i = 0; i < options.objectCount; ++i) {
        rootChildren.push_back(i);
    }
    document["buffers"].push_back({{"byteLength", binary.size()}});
    document["scenes"] = {{{"nodes", rootChildren}}};

    return writeGlb(document, binary.take());
}

}  // namespace encore::scene
