#pragma once

// GltfBuilder assembles tiny glTF 2.0 assets in code for tests.
//
// All binary data goes into one buffer (buffer 0), appended 4-byte aligned. Each add* function
// returns the glTF index of what it added. json() exposes the document so a test can corrupt or
// extend any field; edits made after the last add* call stick (add* functions only append array
// entries and update buffers[0].byteLength).
//
// Output: toGltf() as JSON text with buffer 0 as a data: uri (or as an external .bin when written
// with writeGltf(..., BufferMode::ExternalBin)), toGlb() as GLB bytes with buffer 0 in the BIN
// chunk. A "uri" a test sets on buffers[0] itself is kept as it is.
//
// Example, one red triangle:
//   GltfBuilder builder;
//   const auto positions = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
//   const auto material = builder.addMaterial({.baseColor = {1, 0, 0, 1}});
//   const auto mesh = builder.addMesh({.attributes = {{"POSITION", positions}},
//                                      .material = material});
//   builder.addScene({builder.addNode({.mesh = mesh})});
//   const std::vector<std::uint8_t> glb = builder.toGlb();
//   auto scene = encore::scene::loadSceneFromMemory(glb, {}, "triangle.glb");

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

namespace encore::test {

// glTF component type enum of a C++ element type.
template <typename T>
constexpr std::uint32_t gltfComponentType() {
    if constexpr (std::is_same_v<T, std::int8_t>) {
        return 5120;
    } else if constexpr (std::is_same_v<T, std::uint8_t>) {
        return 5121;
    } else if constexpr (std::is_same_v<T, std::int16_t>) {
        return 5122;
    } else if constexpr (std::is_same_v<T, std::uint16_t>) {
        return 5123;
    } else if constexpr (std::is_same_v<T, std::uint32_t>) {
        return 5125;
    } else {
        static_assert(std::is_same_v<T, float>, "glTF components are i8/u8/i16/u16/u32/f32");
        return 5126;
    }
}

class GltfBuilder {
  public:
    enum class BufferMode { DataUri, ExternalBin };

    struct AccessorOptions {
        bool normalized = false;
        std::optional<std::uint32_t> byteStride;  // Of a new bufferView; absent: tightly packed.
        bool minMax = false;                      // Write min/max computed from the values.
    };

    struct PrimitiveDesc {
        std::map<std::string, std::uint32_t> attributes;  // "POSITION" → accessor.
        std::optional<std::uint32_t> indices;
        std::optional<std::uint32_t> material;
        std::optional<std::uint32_t> mode;  // Absent: glTF default (4, triangles).
    };

    struct NodeDesc {
        std::optional<std::uint32_t> mesh;
        std::vector<std::uint32_t> children;
        std::optional<glm::vec3> translation;
        std::optional<glm::quat> rotation;  // glm order (w, x, y, z); written as glTF x, y, z, w.
        std::optional<glm::vec3> scale;
        std::optional<glm::mat4> matrix;  // Written instead of TRS when set.
        std::string name;
    };

    struct MaterialDesc {
        glm::vec4 baseColor{1.0f};
        float metallic = 0.0f;
        float roughness = 1.0f;
        std::string alphaMode = "OPAQUE";
        std::optional<float> alphaCutoff;
        bool doubleSided = false;
        std::optional<std::uint32_t> baseColorTexture;
    };

    GltfBuilder();

    nlohmann::json& json() { return mJson; }
    const nlohmann::json& json() const { return mJson; }
    std::vector<std::uint8_t>& bufferBytes() { return mBuffer; }

    // Appends raw bytes to buffer 0 (4-byte aligned) and returns the new bufferView.
    std::uint32_t addBufferView(std::span<const std::uint8_t> bytes,
                                std::optional<std::uint32_t> byteStride = {});
    // An accessor on an existing bufferView.
    std::uint32_t addAccessor(std::uint32_t bufferView,
                              std::uint32_t componentType,
                              std::uint32_t count,
                              const std::string& type,
                              std::uint64_t byteOffset = 0,
                              bool normalized = false);

    // Values are components in order: `type` ("SCALAR", "VEC2".."VEC4") says how many make one
    // element. Creates a bufferView (with options.byteStride, padding each element) and an
    // accessor over it.
    template <typename T>
    std::uint32_t addAccessor(const std::vector<T>& values,
                              const std::string& type,
                              const AccessorOptions& options = {}) {
        std::vector<double> asDouble(values.begin(), values.end());
        std::vector<std::uint8_t> bytes(values.size() * sizeof(T));
        std::memcpy(bytes.data(), values.data(), bytes.size());
        return addTypedAccessor(bytes, asDouble, sizeof(T), gltfComponentType<T>(), type, options);
    }

    // Float VEC3 positions with min/max, as glTF requires for POSITION.
    std::uint32_t addPositions(const std::vector<glm::vec3>& positions);
    std::uint32_t addNormals(const std::vector<glm::vec3>& normals);
    std::uint32_t addTexcoords(const std::vector<glm::vec2>& texcoords);
    std::uint32_t addColors(const std::vector<glm::vec4>& colors);
    // A quad from `min` to `max` in x and y at depth `z`, facing +Z: POSITION, NORMAL, TEXCOORD_0
    // (the whole texture, u along +x, v along -y) and two triangles; no material.
    PrimitiveDesc addFacingQuad(glm::vec2 min, glm::vec2 max, float z = 0.0f);
    // SCALAR indices of the given integer type (uint8_t, uint16_t or uint32_t).
    template <typename T>
    std::uint32_t addIndices(const std::vector<T>& indices) {
        return addAccessor(indices, "SCALAR");
    }

    std::uint32_t addMesh(const std::vector<PrimitiveDesc>& primitives,
                          const std::string& name = {});
    std::uint32_t addMesh(const PrimitiveDesc& primitive) {
        return addMesh(std::vector{primitive});
    }
    std::uint32_t addNode(const NodeDesc& node);
    std::uint32_t addMaterial(const MaterialDesc& material);
    // An image from a uri (relative file or data:) and a texture using it; returns the texture.
    std::uint32_t addTexture(const std::string& imageUri,
                             std::optional<std::uint32_t> sampler = {});
    std::uint32_t addSampler(std::optional<std::uint32_t> magFilter,
                             std::optional<std::uint32_t> minFilter,
                             std::uint32_t wrapS = 10497,
                             std::uint32_t wrapT = 10497);
    // Adds a scene; the first one added becomes the default ("scene": 0).
    std::uint32_t addScene(const std::vector<std::uint32_t>& nodes);

    std::string toGltf() const;  // buffer 0 as a data: uri.
    std::vector<std::uint8_t> toGltfBytes() const;
    std::vector<std::uint8_t> toGlb() const;

    // Writes <dir>/<name>.gltf (and <name>.bin beside it with BufferMode::ExternalBin).
    std::filesystem::path writeGltf(const std::filesystem::path& dir,
                                    const std::string& name,
                                    BufferMode mode = BufferMode::DataUri) const;
    std::filesystem::path writeGlb(const std::filesystem::path& dir, const std::string& name) const;

  private:
    std::uint32_t addTypedAccessor(const std::vector<std::uint8_t>& bytes,
                                   const std::vector<double>& values,
                                   std::size_t componentSize,
                                   std::uint32_t componentType,
                                   const std::string& type,
                                   const AccessorOptions& options);
    nlohmann::json finalJson(std::optional<std::string> bufferUri) const;
    std::uint32_t append(const char* array, nlohmann::json value);

    nlohmann::json mJson;
    std::vector<std::uint8_t> mBuffer;
};

// A triangle fan (mode 6) of two indices, with its own NORMAL: no triangle, so the loader
// rewrites its indices into a count-0 accessor in a new, empty buffer (issue 32's case).
GltfBuilder fanWithoutTriangles();

// Builds GLB bytes from JSON text and an optional BIN chunk (no validation: tests corrupt them).
std::vector<std::uint8_t> makeGlb(const std::string& jsonText,
                                  std::span<const std::uint8_t> bin = {});

}  // namespace encore::test
