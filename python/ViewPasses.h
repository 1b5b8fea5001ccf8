#pragma once

// render_views' passes and shading keywords (Renderer.render_views(..., passes=(...))): which
// images a call draws, how they are lit and tone mapped, and the NumPy arrays they become.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "batch/ViewStrips.h"
#include "encore/batch/ViewImages.h"
#include "encore/image/ImageCodec.h"
#include "encore/render/Renderer.h"
#include "encore/render/RendererOptions.h"

namespace encore::python {

namespace py = pybind11;

// The names of `passes` ("rgba", "albedo", "normal", "material", "segmentation", "depth",
// "hdr", "coordinates"), in the order given; ValueError for an unknown or repeated one.
std::vector<batch::ViewImage> passKinds(const py::object& passes);
// "node", "mesh" or "material".
batch::SegmentationBy segmentationBy(const std::string& name);

// What the passes' values mean (docs/batch.md#conventions): `encore batch`'s conventions that
// apply to arrays, and the axes of the returned cameras.
struct PassConventions {
    batch::DepthKind depthKind = batch::DepthKind::Z;
    batch::DepthUnit depthUnit = batch::DepthUnit::Normalized;
    batch::NormalSpace normalSpace = batch::NormalSpace::World;
    batch::NormalKind normalKind = batch::NormalKind::Shading;
    batch::NormalFormat normalFormat = batch::NormalFormat::Png8;
    batch::CameraConvention camera = batch::CameraConvention::OpenGl;

    bool operator==(const PassConventions&) const = default;
};
// From the keywords (no camera convention: OpenGL's); ValueError naming the keyword and its
// values for a value it does not know.
PassConventions passConventions(const std::string& depthKind,
                                const std::string& depthUnit,
                                const std::string& normalSpace,
                                const std::string& normalKind,
                                const std::string& normalFormat,
                                const std::optional<std::string>& cameraConvention);

// Sets the passes `kinds` names in `images` (Color changes nothing), and their conventions.
void applyPassKinds(std::span<const batch::ViewImage> kinds,
                    const PassConventions& conventions,
                    batch::ExtraImages& images);

// render's shading options as keywords.
struct ViewShading {
    std::string environment;  // A Radiance .hdr; empty: the studio environment.
    float intensity = 1.0f;
    float rotationDegrees = 0.0f;
    float exposure = 1.0f;
    render::ToneMapping toneMapping = render::ToneMapping::PbrNeutral;
    render::BackgroundKind background = render::BackgroundKind::Transparent;
    glm::vec3 backgroundColor{0.0f};
};
// From the keywords; ValueError for a tone mapping or background it does not know.
ViewShading viewShading(const py::object& environment,
                        float intensity,
                        float rotationDegrees,
                        float exposure,
                        const std::string& toneMapping,
                        const std::string& background);

// The images of one pass, all views: 8-bit RGBA ones or floats (depth, segmentation, HDR,
// coordinates, normals in a convention but the default).
struct PassImages {
    std::vector<image::ImageRgba8> rgba;
    std::vector<std::vector<float>> floats;
};

// The pass's NumPy array: uint8 (N, H, W, 4) for rgba, albedo, normal and material, float32
// (N, H, W) for depth, uint16 (N, H, W) for segmentation, float32 (N, H, W, 4) for hdr and
// coordinates; normals read as floats as `normalFormat` stores them (uint8 or uint16 n * 0.5 +
// 0.5, or float32 n), each with the coverage as alpha.
py::array passArray(batch::ViewImage kind,
                    const PassImages& images,
                    std::uint32_t width,
                    std::uint32_t height,
                    batch::NormalFormat normalFormat);

// Lights and tone maps `renderer` as `shading` says; `loaded` names the environment it holds
// ("" for the studio one) and is updated when another is loaded.
Result<void> applyShading(render::Renderer& renderer,
                          const ViewShading& shading,
                          std::string& loaded);

// Draws `kinds` of the views (the scene `renderer` prepared, normalised by `bounds`), one
// PassImages per kind, in order: with the renderer's pass targets (RendererOptions::passTargets)
// one frame per target for them all, else one frame per pass. Depth and normals follow
// `conventions` as `encore batch` writes them.
Result<std::vector<PassImages>> renderPasses(render::Renderer& renderer,
                                             const scene::Bounds& bounds,
                                             std::span<const batch::ViewCamera> views,
                                             const batch::ViewRigOptions& rig,
                                             const batch::StripLayout& layout,
                                             std::span<const batch::ViewImage> kinds,
                                             batch::SegmentationBy by,
                                             const PassConventions& conventions);

// The name render_views uses for `kind`.
const char* passName(batch::ViewImage kind);

}  // namespace encore::python
