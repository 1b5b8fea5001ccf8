#pragma once

// The images a batch writes per view, and their names: "000.png" (colour), "000_normal.png"
// (world-space normals) and "000_depth.png" (16-bit depth), the stem having at least three
// digits.

#include <cstddef>
#include <cstdint>
#include <string>

namespace encore::batch {

enum class ViewImage {
    Color,   // RGBA, straight alpha.
    Normal,  // World-space shading normals as n * 0.5 + 0.5, with the colour image's alpha.
    Depth,   // 16-bit greyscale: distance along the camera axis / depth_scale; 0 where less than
             // half of the pixel is covered.
};

// The images beside the colour ones (encore batch --normals, --depth).
struct ExtraImages {
    bool normals = false;
    bool depth = false;

    std::uint32_t perView() const { return 1 + (normals ? 1 : 0) + (depth ? 1 : 0); }
};

// View `index`'s image name without extension: "000", "001_normal", "002_depth", ...
std::string viewStem(std::size_t index, ViewImage kind = ViewImage::Color);

}  // namespace encore::batch
