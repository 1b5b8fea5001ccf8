#pragma once

// The images a batch writes per view, and their names: "000.png" (colour), "000_normal.png",
// "000_depth.png" (or .exr), "000_albedo.png", "000_material.png", "000_segmentation.png",
// "000_hdr.exr" and "000_coordinates.png" (or .exr), the stem having at least three digits
// (docs/batch.md#passes).

#include <cstddef>
#include <cstdint>
#include <string>

namespace encore::batch {

enum class ViewImage {
    Color,     // RGBA, straight alpha.
    Normal,    // World-space shading normals as n * 0.5 + 0.5, with the colour image's alpha.
    Depth,     // 16-bit greyscale: distance along the camera axis / depth_scale; 0 where less than
               // half of the pixel is covered. EXR: the distance itself, infinity where empty.
    Albedo,    // Base colour (texture x factor x vertex colour), sRGB, with the colour's alpha.
    Material,  // Linear R occlusion, G roughness, B metallic, with the colour's alpha.
    Segmentation,  // 16-bit: 0 background, else 1 + the node (mesh, material) index.
    Hdr,           // Linear radiance before exposure and tone mapping, half-float EXR.
    // Each pixel's position in the normalised model box mapped into [0, 1]^3 (NOCS), 16-bit RGBA
    // with the coverage as alpha, or half-float EXR; 0 where nothing is drawn.
    Coordinates,
};

enum class DepthFormat { Png, Exr };
// What a depth value measures (encore batch --depth-kind, docs/batch.md#conventions).
enum class DepthKind {
    Z,    // Along the camera's axis: the distance from the image plane through the camera centre.
    Ray,  // Along the pixel's ray from the camera centre (Z / cos of the ray's angle to the axis;
          // the same as Z for an orthographic view, whose rays are parallel to the axis).
};
// The unit of depth values (encore batch --depth-unit).
enum class DepthUnit {
    Normalized,  // The batch's normalised scene (the model fitted into the unit box).
    Model,       // The model's own units (glTF's metres): the normalisation's scale undone.
};
// The axes normals are expressed in (encore batch --normal-space).
enum class NormalSpace {
    World,   // The glTF world's.
    Camera,  // The view's camera's, in the cameras' convention (BatchOptions::cameraConvention).
};
// Which normal (encore batch --normal-kind).
enum class NormalKind {
    Shading,    // The normal the surface is shaded with: interpolated, normal-mapped.
    Geometric,  // The triangle's own.
};
// How object coordinates are stored (encore batch --coordinates-format).
enum class CoordinatesFormat { Png16, Exr };
// How normals are stored (encore batch --normal-format).
enum class NormalFormat {
    Png8,   // RGBA8: n * 0.5 + 0.5.
    Png16,  // RGBA16: n * 0.5 + 0.5.
    Exr,    // Half-float RGBA: n itself, alpha the coverage.
};
// What a segmentation id counts (encore batch --segmentation-by).
enum class SegmentationBy { Node, Mesh, Material };

// How the passes that share the colour frame's camera are drawn (docs/batch.md#passes).
enum class PassDrawing {
    Targets,  // In the colour frame's render pass, as more colour targets (the default).
    Frames,   // One more frame per pass through a debug channel (--pass-frames: to compare).
};

// The images beside the colour ones (encore batch --normals, --depth, --albedo, ...).
struct ExtraImages {
    bool normals = false;
    bool depth = false;
    bool albedo = false;
    bool material = false;
    bool segmentation = false;
    bool hdr = false;
    bool coordinates = false;
    DepthFormat depthFormat = DepthFormat::Png;
    DepthKind depthKind = DepthKind::Z;
    DepthUnit depthUnit = DepthUnit::Normalized;
    NormalSpace normalSpace = NormalSpace::World;
    NormalKind normalKind = NormalKind::Shading;
    NormalFormat normalFormat = NormalFormat::Png8;
    CoordinatesFormat coordinatesFormat = CoordinatesFormat::Png16;
    SegmentationBy segmentationBy = SegmentationBy::Node;
    PassDrawing drawing = PassDrawing::Targets;

    std::uint32_t perView() const {
        return 1 + std::uint32_t(normals) + std::uint32_t(depth) + std::uint32_t(albedo) +
               std::uint32_t(material) + std::uint32_t(segmentation) + std::uint32_t(hdr) +
               std::uint32_t(coordinates);
    }
    // Whether normals are read back as floats and converted on the CPU (any normal convention
    // but the default's: world-space shading normals in 8 bits, which the GPU writes as they are).
    bool normalsAsFloats() const {
        return normals && (normalSpace != NormalSpace::World || normalKind != NormalKind::Shading ||
                           normalFormat != NormalFormat::Png8);
    }
    bool operator==(const ExtraImages&) const = default;
};

// View `index`'s image name without extension: "000", "001_normal", "002_depth", ...
std::string viewStem(std::size_t index, ViewImage kind = ViewImage::Color);
// ".png", or ".exr" for HDR images and EXR depth, normals and coordinates.
std::string viewExtension(ViewImage kind, const ExtraImages& extras = {});

}  // namespace encore::batch
