#pragma once

// The images a batch writes per view, and their names: "000.png" (colour), "000_normal.png",
// "000_depth.png" (or .exr), "000_albedo.png", "000_material.png", "000_segmentation.png" and
// "000_hdr.exr", the stem having at least three digits (docs/batch.md#passes).

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
};

enum class DepthFormat { Png, Exr };
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
    DepthFormat depthFormat = DepthFormat::Png;
    SegmentationBy segmentationBy = SegmentationBy::Node;
    PassDrawing drawing = PassDrawing::Targets;

    std::uint32_t perView() const {
        return 1 + std::uint32_t(normals) + std::uint32_t(depth) + std::uint32_t(albedo) +
               std::uint32_t(material) + std::uint32_t(segmentation) + std::uint32_t(hdr);
    }
    bool operator==(const ExtraImages&) const = default;
};

// View `index`'s image name without extension: "000", "001_normal", "002_depth", ...
std::string viewStem(std::size_t index, ViewImage kind = ViewImage::Color);
// ".png", or ".exr" for HDR images and EXR depth.
std::string viewExtension(ViewImage kind, const ExtraImages& extras = {});

}  // namespace encore::batch
