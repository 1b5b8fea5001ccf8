#include "encore/batch/ViewImages.h"

#include <cstdio>

namespace encore::batch {

std::string viewStem(std::size_t index, ViewImage kind) {
    char stem[32];
    std::snprintf(stem, sizeof(stem), "%03zu", index);
    switch (kind) {
        case ViewImage::Normal:
            return std::string(stem) + "_normal";
        case ViewImage::Depth:
            return std::string(stem) + "_depth";
        case ViewImage::Albedo:
            return std::string(stem) + "_albedo";
        case ViewImage::Material:
            return std::string(stem) + "_material";
        case ViewImage::Segmentation:
            return std::string(stem) + "_segmentation";
        case ViewImage::Hdr:
            return std::string(stem) + "_hdr";
        case ViewImage::Coordinates:
            return std::string(stem) + "_coordinates";
        case ViewImage::Color:
            break;
    }
    return stem;
}

std::string viewExtension(ViewImage kind, const ExtraImages& extras) {
    const bool exr =
        kind == ViewImage::Hdr ||
        (kind == ViewImage::Depth && extras.depthFormat == DepthFormat::Exr) ||
        (kind == ViewImage::Normal && extras.normalFormat == NormalFormat::Exr) ||
        (kind == ViewImage::Coordinates && extras.coordinatesFormat == CoordinatesFormat::Exr);
    return exr ? ".exr" : ".png";
}

}  // namespace encore::batch
