#include "batch/PointCloud.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <string>

#include "batch/ModelSeed.h"
#include "image/Srgb.h"
#include "scene/TriangleCorners.h"

namespace encore::batch {
namespace {

// One triangle of the scene in the normalised frame, with what its points take from its
// vertices.
struct Triangle {
    glm::vec3 position[3];
    glm::vec3 normal[3];
    glm::vec4 color[3];  // Factor x vertex colour, linear.
    glm::vec2 texcoord[3];
    const scene::Image* texture = nullptr;  // Base colour, decoded; null: none.
    scene::Wrap wrapS = scene::Wrap::Repeat;
    scene::Wrap wrapT = scene::Wrap::Repeat;
};

float wrapped(float t, scene::Wrap wrap) {
    switch (wrap) {
        case scene::Wrap::ClampToEdge:
            return std::clamp(t, 0.0f, 1.0f);
        case scene::Wrap::MirroredRepeat: {
            const float period = t - 2.0f * std::floor(t * 0.5f);
            return period > 1.0f ? 2.0f - period : period;
        }
        case scene::Wrap::Repeat:
            break;
    }
    return t - std::floor(t);
}

// The texel nearest `uv`, linear (the base colour texture is sRGB-encoded).
glm::vec4 textureAt(const Triangle& triangle, glm::vec2 uv) {
    const scene::Image& image = *triangle.texture;
    const float u = wrapped(uv.x, triangle.wrapS);
    const float v = wrapped(uv.y, triangle.wrapT);
    const auto x = std::min(std::uint32_t(u * float(image.width)), image.width - 1);
    const auto y = std::min(std::uint32_t(v * float(image.height)), image.height - 1);
    const std::uint8_t* texel = &image.rgba8[(std::size_t(y) * image.width + x) * 4];
    return {float(image::srgbToLinear(texel[0] / 255.0)),
            float(image::srgbToLinear(texel[1] / 255.0)),
            float(image::srgbToLinear(texel[2] / 255.0)), texel[3] / 255.0f};
}

std::vector<Triangle> sceneTriangles(const scene::SceneData& scene,
                                     const glm::mat4& normalization) {
    std::vector<Triangle> triangles;
    for (const scene::Instance& instance : scene.instances) {
        const glm::mat4 toFrame = normalization * instance.world;
        const glm::mat3 normalMatrix(instance.normalMatrix);
        for (const scene::Primitive& primitive : scene.meshes[instance.mesh.index()].primitives) {
            const std::vector<std::uint32_t> corners = scene::triangleCorners(scene, primitive);
            const auto position = primitive.attribute(scene::Semantic::Position);
            if (corners.empty() || !position) {
                continue;
            }
            const std::vector<glm::vec4> positions = scene.readFloats(*position);
            const auto normalAccessor = primitive.attribute(scene::Semantic::Normal);
            const std::vector<glm::vec4> normals =
                normalAccessor ? scene.readFloats(*normalAccessor) : std::vector<glm::vec4>{};
            const auto colorAccessor = primitive.attribute(scene::Semantic::Color0);
            const std::vector<glm::vec4> colors =
                colorAccessor ? scene.readFloats(*colorAccessor) : std::vector<glm::vec4>{};
            const scene::Material& material = scene.materials[primitive.material.index()];
            Triangle shared;
            std::vector<glm::vec4> texcoords;
            if (material.baseColorTexture) {
                const scene::Texture& texture =
                    scene.textures[material.baseColorTexture->texture.index()];
                const auto uvAccessor = primitive.attribute(material.baseColorTexture->texCoord == 1
                                                                ? scene::Semantic::Texcoord1
                                                                : scene::Semantic::Texcoord0);
                if (texture.image.valid() && uvAccessor) {
                    const scene::Image& image = scene.images[texture.image.index()];
                    // The loader may have handed the pixels on to the GPU's staging already.
                    if (image.width > 0 && image.height > 0 &&
                        image.rgba8.size() >= std::size_t(image.width) * image.height * 4) {
                        shared.texture = &image;
                        texcoords = scene.readFloats(*uvAccessor);
                        const scene::Sampler& sampler = scene.samplers[texture.sampler.index()];
                        shared.wrapS = sampler.wrapS;
                        shared.wrapT = sampler.wrapT;
                    }
                }
            }
            for (std::size_t i = 0; i + 2 < corners.size(); i += 3) {
                Triangle triangle = shared;
                bool inside = true;
                for (int c = 0; c < 3; ++c) {
                    const std::uint32_t v = corners[i + c];
                    if (v >= positions.size()) {
                        inside = false;  // The loader checks indices; this only guards.
                        break;
                    }
                    triangle.position[c] =
                        glm::vec3(toFrame * glm::vec4(glm::vec3(positions[v]), 1.0f));
                    triangle.normal[c] =
                        v < normals.size() ? normalMatrix * glm::vec3(normals[v]) : glm::vec3(0.0f);
                    triangle.color[c] = material.baseColorFactor *
                                        (v < colors.size() ? colors[v] : glm::vec4(1.0f));
                    triangle.texcoord[c] =
                        v < texcoords.size() ? glm::vec2(texcoords[v]) : glm::vec2(0.0f);
                }
                if (inside) {
                    triangles.push_back(triangle);
                }
            }
        }
    }
    return triangles;
}

template <typename T>
void append(std::vector<std::uint8_t>& bytes, T value) {
    static_assert(std::endian::native == std::endian::little, "PLY binary_little_endian");
    const auto* raw = reinterpret_cast<const std::uint8_t*>(&value);
    bytes.insert(bytes.end(), raw, raw + sizeof(T));
}

}  // namespace

std::vector<SurfacePoint> samplePointCloud(const scene::SceneData& scene,
                                           const glm::mat4& normalization,
                                           std::uint32_t count,
                                           std::uint64_t seed) {
    const std::vector<Triangle> triangles = sceneTriangles(scene, normalization);
    // Each triangle's share of the area, summed in doubles so that a million small triangles
    // keep their weight.
    std::vector<double> cumulative(triangles.size());
    double total = 0.0;
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        const glm::dvec3 a(triangles[i].position[0]);
        const glm::dvec3 b(triangles[i].position[1]);
        const glm::dvec3 c(triangles[i].position[2]);
        const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
        total += std::isfinite(area) ? area : 0.0;
        cumulative[i] = total;
    }
    std::vector<SurfacePoint> points;
    if (!(total > 0.0)) {
        return points;
    }
    std::mt19937_64 draws = randomStream(seed, RandomStream::PointCloud);
    points.reserve(count);
    for (std::uint32_t n = 0; n < count; ++n) {
        const double pick = unitInterval(draws) * total;
        const std::size_t index = std::min<std::size_t>(
            std::size_t(std::upper_bound(cumulative.begin(), cumulative.end(), pick) -
                        cumulative.begin()),
            triangles.size() - 1);
        const Triangle& triangle = triangles[index];
        // Uniform over the triangle: sqrt(r1) folds the square onto it without bias.
        const double root = std::sqrt(unitInterval(draws));
        const double r2 = unitInterval(draws);
        const float w0 = float(1.0 - root);
        const float w1 = float(root * (1.0 - r2));
        const float w2 = float(root * r2);
        SurfacePoint point;
        point.position =
            w0 * triangle.position[0] + w1 * triangle.position[1] + w2 * triangle.position[2];
        const glm::vec3 normal =
            w0 * triangle.normal[0] + w1 * triangle.normal[1] + w2 * triangle.normal[2];
        point.normal = glm::length(normal) > 1e-12f ? glm::normalize(normal) : glm::vec3(0.0f);
        glm::vec4 color = w0 * triangle.color[0] + w1 * triangle.color[1] + w2 * triangle.color[2];
        if (triangle.texture) {
            color *= textureAt(triangle, w0 * triangle.texcoord[0] + w1 * triangle.texcoord[1] +
                                             w2 * triangle.texcoord[2]);
        }
        for (int c = 0; c < 3; ++c) {
            point.color[c] = image::linearToSrgb8(std::clamp(color[c], 0.0f, 1.0f));
        }
        point.color[3] = std::uint8_t(std::lround(std::clamp(color[3], 0.0f, 1.0f) * 255.0f));
        points.push_back(point);
    }
    return points;
}

std::vector<std::uint8_t> encodePly(const std::vector<SurfacePoint>& points) {
    const std::string header =
        "ply\nformat binary_little_endian 1.0\ncomment encore batch --point-cloud: normalised "
        "frame, colours sRGB\nelement vertex " +
        std::to_string(points.size()) +
        "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty "
        "float ny\nproperty float nz\nproperty uchar red\nproperty uchar green\nproperty uchar "
        "blue\nproperty uchar alpha\nend_header\n";
    std::vector<std::uint8_t> bytes(header.begin(), header.end());
    bytes.reserve(bytes.size() + points.size() * 28);
    for (const SurfacePoint& point : points) {
        for (int c = 0; c < 3; ++c) {
            append(bytes, point.position[c]);
        }
        for (int c = 0; c < 3; ++c) {
            append(bytes, point.normal[c]);
        }
        for (int c = 0; c < 4; ++c) {
            append(bytes, point.color[c]);
        }
    }
    return bytes;
}

}  // namespace encore::batch
