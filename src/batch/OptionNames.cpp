#include "batch/OptionNames.h"

#include <array>

namespace encore::batch {

namespace {

constexpr std::array<NamedValue<CameraDistribution>, 5> kCameraDistributions{{
    {"orbit", CameraDistribution::Orbit},
    {"sphere", CameraDistribution::Sphere},
    {"upper-hemisphere", CameraDistribution::UpperHemisphere},
    {"hammersley", CameraDistribution::Hammersley},
    {"fibonacci", CameraDistribution::Fibonacci},
}};
constexpr std::array<NamedValue<Projection>, 2> kProjections{{
    {"perspective", Projection::Perspective},
    {"orthographic", Projection::Orthographic},
}};
constexpr std::array<NamedValue<CameraConvention>, 3> kCameraConventions{{
    {"opengl", CameraConvention::OpenGl},
    {"opencv", CameraConvention::OpenCv},
    {"blender", CameraConvention::Blender},
}};
constexpr std::array<NamedValue<OutputLayout>, 3> kOutputLayouts{{
    {"nerf", OutputLayout::Nerf},
    {"objaverse", OutputLayout::Objaverse},
    {"gobjaverse", OutputLayout::Gobjaverse},
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
constexpr std::array<NamedValue<DepthKind>, 2> kDepthKinds{{
    {"z", DepthKind::Z},
    {"ray", DepthKind::Ray},
}};
constexpr std::array<NamedValue<DepthUnit>, 2> kDepthUnits{{
    {"normalized", DepthUnit::Normalized},
    {"model", DepthUnit::Model},
}};
constexpr std::array<NamedValue<NormalSpace>, 2> kNormalSpaces{{
    {"world", NormalSpace::World},
    {"camera", NormalSpace::Camera},
}};
constexpr std::array<NamedValue<NormalKind>, 2> kNormalKinds{{
    {"shading", NormalKind::Shading},
    {"geometric", NormalKind::Geometric},
}};
constexpr std::array<NamedValue<NormalFormat>, 3> kNormalFormats{{
    {"png8", NormalFormat::Png8},
    {"png16", NormalFormat::Png16},
    {"exr", NormalFormat::Exr},
}};
constexpr std::array<NamedValue<CoordinatesFormat>, 2> kCoordinatesFormats{{
    {"png16", CoordinatesFormat::Png16},
    {"exr", CoordinatesFormat::Exr},
}};
// Python's passes=, and what the arrays of render_views' dict are called.
constexpr std::array<NamedValue<ViewImage>, 8> kPasses{{
    {"rgba", ViewImage::Color},
    {"albedo", ViewImage::Albedo},
    {"normal", ViewImage::Normal},
    {"material", ViewImage::Material},
    {"segmentation", ViewImage::Segmentation},
    {"depth", ViewImage::Depth},
    {"hdr", ViewImage::Hdr},
    {"coordinates", ViewImage::Coordinates},
}};
constexpr std::array<NamedValue<image::PngCompression>, 2> kPngCompressions{{
    {"small", image::PngCompression::Small},
    {"fast", image::PngCompression::Fast},
}};
constexpr std::array<NamedValue<render::ToneMapping>, 3> kToneMappings{{
    {"neutral", render::ToneMapping::PbrNeutral},
    {"aces", render::ToneMapping::AcesHill},
    {"none", render::ToneMapping::None},
}};
constexpr std::array<NamedValue<render::DebugChannel>, 14> kDebugChannels{{
    {"none", render::DebugChannel::Shaded},
    {"base-color", render::DebugChannel::BaseColor},
    {"normal", render::DebugChannel::Normal},
    {"metallic", render::DebugChannel::Metallic},
    {"roughness", render::DebugChannel::Roughness},
    {"occlusion", render::DebugChannel::Occlusion},
    {"emissive", render::DebugChannel::Emissive},
    {"depth", render::DebugChannel::Depth},
    {"material", render::DebugChannel::Material},
    {"segment-node", render::DebugChannel::SegmentNode},
    {"segment-mesh", render::DebugChannel::SegmentMesh},
    {"segment-material", render::DebugChannel::SegmentMaterial},
    {"geometric-normal", render::DebugChannel::GeometricNormal},
    {"position", render::DebugChannel::Position},
}};

}  // namespace

NameTable<CameraDistribution> cameraDistributionNames() {
    return kCameraDistributions;
}

NameTable<Projection> projectionNames() {
    return kProjections;
}

NameTable<CameraConvention> cameraConventionNames() {
    return kCameraConventions;
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
NameTable<DepthKind> depthKindNames() {
    return kDepthKinds;
}
NameTable<DepthUnit> depthUnitNames() {
    return kDepthUnits;
}
NameTable<NormalSpace> normalSpaceNames() {
    return kNormalSpaces;
}
NameTable<NormalKind> normalKindNames() {
    return kNormalKinds;
}
NameTable<NormalFormat> normalFormatNames() {
    return kNormalFormats;
}
NameTable<CoordinatesFormat> coordinatesFormatNames() {
    return kCoordinatesFormats;
}
NameTable<ViewImage> passNames() {
    return kPasses;
}
NameTable<image::PngCompression> pngCompressionNames() {
    return kPngCompressions;
}
NameTable<render::ToneMapping> toneMappingNames() {
    return kToneMappings;
}
NameTable<render::DebugChannel> debugChannelNames() {
    return kDebugChannels;
}

std::string nameList(const std::vector<std::string>& names) {
    std::string list;
    for (std::size_t i = 0; i < names.size(); ++i) {
        list += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
    }
    return list;
}

}  // namespace encore::batch
