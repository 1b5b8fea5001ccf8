#include "batch/OptionNames.h"

#include <array>

namespace encore::batch {

namespace {

constexpr std::array<NamedValue<CameraDistribution>, 3> kCameraDistributions{{
    {"orbit", CameraDistribution::Orbit},
    {"sphere", CameraDistribution::Sphere},
    {"upper-hemisphere", CameraDistribution::UpperHemisphere},
}};
constexpr std::array<NamedValue<OutputLayout>, 2> kOutputLayouts{{
    {"nerf", OutputLayout::Nerf},
    {"objaverse", OutputLayout::Objaverse},
}};
constexpr std::array<NamedValue<PngFiltering>, 3> kPngFilterings{{
    {"auto", PngFiltering::Auto},
    {"gpu", PngFiltering::Gpu},
    {"cpu", PngFiltering::Cpu},
}};
constexpr std::array<NamedValue<SegmentationBy>, 3> kSegmentationBy{{
    {"node", SegmentationBy::Node},
    {"mesh", SegmentationBy::Mesh},
    {"material", SegmentationBy::Material},
}};
constexpr std::array<NamedValue<DepthFormat>, 2> kDepthFormats{{
    {"png", DepthFormat::Png},
    {"exr", DepthFormat::Exr},
}};

}  // namespace

NameTable<CameraDistribution> cameraDistributionNames() {
    return kCameraDistributions;
}
NameTable<OutputLayout> outputLayoutNames() {
    return kOutputLayouts;
}
NameTable<PngFiltering> pngFilteringNames() {
    return kPngFilterings;
}
NameTable<SegmentationBy> segmentationByNames() {
    return kSegmentationBy;
}
NameTable<DepthFormat> depthFormatNames() {
    return kDepthFormats;
}

std::string nameList(const std::vector<std::string>& names) {
    std::string list;
    for (std::size_t i = 0; i < names.size(); ++i) {
        list += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
    }
    return list;
}

}  // namespace encore::batch
