#pragma once

// The names that `encore batch` and Python's batch() give the values of the batch's
// enumerations (and of the renderer's that its options set: tone mapping, debug channels): one
// table per enumeration, which every front parses and lists, so that a value is named once (as
// render::strategyFromName names the strategies).

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "encore/batch/Batch.h"
#include "encore/batch/ViewImages.h"
#include "encore/batch/ViewRig.h"
#include "encore/core/Result.h"
#include "encore/image/ImageCodec.h"
#include "encore/render/RendererOptions.h"
#include "render/Lighting.h"

namespace encore::batch {

template <class Enum>
struct NamedValue {
    std::string_view name;
    Enum value;
};

template <class Enum>
using NameTable = std::span<const NamedValue<Enum>>;

NameTable<CameraDistribution> cameraDistributionNames();  // orbit, sphere, ..., fibonacci
NameTable<Projection> projectionNames();                  // perspective, orthographic
NameTable<CameraConvention> cameraConventionNames();      // opengl, opencv, blender
NameTable<OutputLayout> outputLayoutNames();              // nerf, objaverse, gobjaverse
NameTable<PngFiltering> pngFilteringNames();              // auto, gpu, cpu
NameTable<SegmentationBy> segmentationByNames();          // node, mesh, material
NameTable<DepthFormat> depthFormatNames();                // png, exr
NameTable<DepthKind> depthKindNames();                    // z, ray
NameTable<DepthUnit> depthUnitNames();                    // normalized, model
NameTable<NormalSpace> normalSpaceNames();                // world, camera
NameTable<NormalKind> normalKindNames();                  // shading, geometric
NameTable<NormalFormat> normalFormatNames();              // png8, png16, exr
NameTable<CoordinatesFormat> coordinatesFormatNames();    // png16, exr
NameTable<image::PngCompression> pngCompressionNames();   // small, fast
NameTable<ViewImage> passNames();                     // rgba, albedo, ..., depth, hdr, coordinates
NameTable<render::ToneMapping> toneMappingNames();    // neutral, aces, none
NameTable<render::DebugChannel> debugChannelNames();  // none, base-color, normal, ...

template <class Enum>
std::optional<Enum> valueNamed(NameTable<Enum> table, std::string_view name) {
    for (const NamedValue<Enum>& entry : table) {
        if (entry.name == name) {
            return entry.value;
        }
    }
    return std::nullopt;
}

// The value's name; the table's first for a value it does not hold.
template <class Enum>
std::string_view nameOf(NameTable<Enum> table, Enum value) {
    for (const NamedValue<Enum>& entry : table) {
        if (entry.value == value) {
            return entry.name;
        }
    }
    return table.front().name;
}

template <class Enum>
std::vector<std::string> namesOf(NameTable<Enum> table) {
    std::vector<std::string> names;
    for (const NamedValue<Enum>& entry : table) {
        names.emplace_back(entry.name);
    }
    return names;
}

// "a, b or c".
std::string nameList(const std::vector<std::string>& names);

// The value named `name`, or an InvalidArgument error naming `option` and the names it takes.
template <class Enum>
Result<Enum> parseNamed(NameTable<Enum> table, std::string_view name, std::string_view option) {
    if (auto value = valueNamed(table, name)) {
        return *value;
    }
    return makeError(ErrorCode::InvalidArgument, std::string(option) + " takes " +
                                                     nameList(namesOf(table)) + " (not '" +
                                                     std::string(name) + "').");
}

}  // namespace encore::batch
