#include "ViewPasses.h"

#include <glm/gtc/constants.hpp>

#include "BatchArguments.h"
#include "batch/DepthConventions.h"
#include "batch/NormalConventions.h"
#include "batch/ObjectCoordinates.h"
#include "batch/OptionValues.h"
#include "batch/PassImages.h"
#include "batch/RgbaPng.h"
#include "encore/image/HdrImage.h"
#include "gpu/Readback.h"

#include <algorithm>
#include <cstring>
#include <optional>

namespace encore::python {
const char* passName(batch::ViewImage kind) {
    return batch::nameOf(batch::passNames(), kind).data();  // The table's names end in a NUL.
}

std::vector<batch::ViewImage> passKinds(const py::object& passes) {
    if (py::isinstance<py::str>(passes)) {
        throw py::value_error("passes takes a sequence of names, such as (\"rgba\", \"depth\").");
    }
    std::vector<batch::ViewImage> kinds;
    for (const py::handle item : passes) {
        const std::string name = py::str(item);
        const auto found = batch::valueNamed(batch::passNames(), name);
        if (!found) {
            throw py::value_error("Unknown pass '" + name + "' (known: " +
                                  batch::nameList(batch::namesOf(batch::passNames())) + ").");
        }
        if (std::find(kinds.begin(), kinds.end(), *found) != kinds.end()) {
            throw py::value_error("The pass '" + name + "' is asked for twice.");
        }
        kinds.push_back(*found);
    }
    if (kinds.empty()) {
        throw py::value_error("passes names no pass.");
    }
    return kinds;
}

batch::SegmentationBy segmentationBy(const std::string& name) {
    return named(batch::segmentationByNames(), name, "segmentation_by");
}

PassConventions passConventions(const std::string& depthKind,
                                const std::string& depthUnit,
                                const std::string& normalSpace,
                                const std::string& normalKind,
                                const std::string& normalFormat,
                                const std::optional<std::string>& cameraConvention) {
    PassConventions conventions;
    conventions.depthKind = named(batch::depthKindNames(), depthKind, "depth_kind");
    conventions.depthUnit = named(batch::depthUnitNames(), depthUnit, "depth_unit");
    conventions.normalSpace = named(batch::normalSpaceNames(), normalSpace, "normal_space");
    conventions.normalKind = named(batch::normalKindNames(), normalKind, "normal_kind");
    conventions.normalFormat = named(batch::normalFormatNames(), normalFormat, "normal_format");
    if (cameraConvention) {
        conventions.camera =
            named(batch::cameraConventionNames(), *cameraConvention, "camera_convention");
    }
    return conventions;
}

void applyPassKinds(std::span<const batch::ViewImage> kinds,
                    const PassConventions& conventions,
                    batch::ExtraImages& images) {
    images.depthKind = conventions.depthKind;
    images.depthUnit = conventions.depthUnit;
    images.normalSpace = conventions.normalSpace;
    images.normalKind = conventions.normalKind;
    images.normalFormat = conventions.normalFormat;
    for (const batch::ViewImage kind : kinds) {
        switch (kind) {
            case batch::ViewImage::Normal:
                images.normals = true;
                break;
            case batch::ViewImage::Depth:
                images.depth = true;
                break;
            case batch::ViewImage::Albedo:
                images.albedo = true;
                break;
            case batch::ViewImage::Material:
                images.material = true;
                break;
            case batch::ViewImage::Segmentation:
                images.segmentation = true;
                break;
            case batch::ViewImage::Hdr:
                images.hdr = true;
                break;
            case batch::ViewImage::Coordinates:
                images.coordinates = true;
                break;
            case batch::ViewImage::Color:
                break;
        }
    }
}

ViewShading viewShading(const py::object& environment,
                        float intensity,
                        float rotationDegrees,
                        float exposure,
                        const std::string& toneMapping,
                        const std::string& background) {
    ViewShading shading;
    if (!environment.is_none()) {
        shading.environment = py::str(environment);
    }
    if (!(intensity >= 0.0f) || !(exposure > 0.0f)) {
        throw py::value_error("environment_intensity must be 0 or more and exposure positive.");
    }
    shading.intensity = intensity;
    shading.rotationDegrees = rotationDegrees;
    shading.exposure = exposure;
    shading.toneMapping = named(batch::toneMappingNames(), toneMapping, "tone_mapping");
    render::ToneMappingOptions parsed;
    if (auto valid = batch::parseBackground(background, "background", parsed); !valid) {
        throw py::value_error(valid.error().message);
    }
    shading.background = parsed.background;
    shading.backgroundColor = parsed.backgroundColor;
    return shading;
}

namespace {

// Normals read as floats (normalVectors), as `format` stores them.
py::array normalArray(const PassImages& images,
                      std::uint32_t width,
                      std::uint32_t height,
                      batch::NormalFormat format) {
    const std::vector<std::size_t> shape{images.floats.size(), height, width, 4};
    if (format == batch::NormalFormat::Exr) {
        py::array_t<float> values(shape);
        float* out = values.mutable_data();
        for (const std::vector<float>& view : images.floats) {
            out = std::copy(view.begin(), view.end(), out);
        }
        return values;
    }
    // The samples of the PNG the batch writes (RgbaPng.h).
    const auto samples = [&]<typename Sample>(Sample* out) {
        const std::uint8_t bits = format == batch::NormalFormat::Png16 ? 16 : 8;
        for (const std::vector<float>& view : images.floats) {
            for (const float value : batch::mappedNormals(view)) {
                *out++ = Sample(batch::pngSample(value, bits));
            }
        }
    };
    if (format == batch::NormalFormat::Png16) {
        py::array_t<std::uint16_t> values(shape);
        samples(values.mutable_data());
        return values;
    }
    py::array_t<std::uint8_t> values(shape);
    samples(values.mutable_data());
    return values;
}

// A depth read-back as the EXR depth of the batch holds it, in the conventions' kind and unit:
// what both drawings of the passes return.
std::vector<float> depthValues(const batch::FloatStrip& pixels,
                               const PassConventions& conventions,
                               float unitsPerModelUnit,
                               const batch::ViewCamera& view) {
    return batch::depthOfKind(
        pixels, conventions.depthKind,
        batch::depthUnitsPerModelUnit(conventions.depthUnit, unitsPerModelUnit), view);
}

}  // namespace

py::array passArray(batch::ViewImage kind,
                    const PassImages& images,
                    std::uint32_t width,
                    std::uint32_t height,
                    batch::NormalFormat normalFormat) {
    const std::size_t h = height, w = width;
    if (!images.rgba.empty() || images.floats.empty()) {
        py::array_t<std::uint8_t> pixels({images.rgba.size(), h, w, std::size_t(4)});
        std::uint8_t* out = pixels.mutable_data();
        for (const image::ImageRgba8& image : images.rgba) {
            std::memcpy(out, image.pixels.data(), image.pixels.size());
            out += image.pixels.size();
        }
        return pixels;
    }
    if (kind == batch::ViewImage::Normal) {
        return normalArray(images, width, height, normalFormat);
    }
    const std::size_t views = images.floats.size();
    if (kind == batch::ViewImage::Segmentation) {
        py::array_t<std::uint16_t> ids({views, h, w});
        std::uint16_t* out = ids.mutable_data();
        for (const std::vector<float>& view : images.floats) {
            out = std::transform(view.begin(), view.end(), out,
                                 [](float id) { return std::uint16_t(id); });
        }
        return ids;
    }
    const bool rgba = kind == batch::ViewImage::Hdr || kind == batch::ViewImage::Coordinates;
    py::array_t<float> values = rgba ? py::array_t<float>({views, h, w, std::size_t(4)})
                                     : py::array_t<float>({views, h, w});
    float* out = values.mutable_data();
    for (const std::vector<float>& view : images.floats) {
        out = std::copy(view.begin(), view.end(), out);
    }
    return values;
}

Result<void> applyShading(render::Renderer& renderer,
                          const ViewShading& shading,
                          std::string& loaded) {
    if (shading.environment != loaded) {
        ENCORE_TRY_ASSIGN(auto panorama,
                          shading.environment.empty()
                              ? Result<image::HdrImage>(image::makeStudioEnvironment())
                              : image::readHdr(shading.environment));
        ENCORE_TRY(renderer.loadEnvironment(panorama));
        loaded = shading.environment;
    }
    render::LightingParameters lighting = renderer.lighting();
    lighting.environmentIntensity = shading.intensity;
    lighting.environmentRotationRadians = glm::radians(shading.rotationDegrees);
    lighting.debugChannel = render::DebugChannel::Shaded;
    renderer.setLighting(lighting);
    render::ToneMappingOptions toneMapping = renderer.toneMapping();
    toneMapping.toneMapping = shading.toneMapping;
    toneMapping.exposure = shading.exposure;
    toneMapping.background = shading.background;
    toneMapping.backgroundColor = shading.backgroundColor;
    return renderer.setToneMapping(toneMapping);
}

namespace {

// renderPasses with the renderer's pass targets: one frame per target draws every pass, each
// image then read from its own texture.
Result<std::vector<PassImages>> renderPassTargets(render::Renderer& renderer,
                                                  const scene::Bounds& bounds,
                                                  std::span<const batch::ViewCamera> views,
                                                  const batch::ViewRigOptions& rig,
                                                  const batch::StripLayout& layout,
                                                  std::span<const batch::ViewImage> kinds,
                                                  const PassConventions& conventions) {
    const glm::mat4 toUnitBox = batch::normalization(bounds, rig.normalize);
    const float unitsPerModelUnit = toUnitBox[0][0];
    std::vector<PassImages> passes(kinds.size());
    for (std::uint32_t first = 0; first < views.size(); first += layout.strips) {
        const std::vector<render::Camera> cameras =
            batch::stripCameras(views, first, layout, toUnitBox);
        renderer.renderViews(cameras);
        const std::uint32_t count =
            std::min<std::uint32_t>(layout.strips, std::uint32_t(views.size()) - first);
        std::optional<std::vector<float>> depthAndId;
        for (std::size_t k = 0; k < kinds.size(); ++k) {
            const batch::ViewImage kind = kinds[k];
            if (kind == batch::ViewImage::Depth || kind == batch::ViewImage::Segmentation ||
                kind == batch::ViewImage::Hdr) {
                std::vector<float> hdr;
                if (kind == batch::ViewImage::Hdr) {
                    ENCORE_TRY_ASSIGN(hdr, renderer.readHdrImage());
                } else if (!depthAndId) {
                    ENCORE_TRY_ASSIGN(depthAndId,
                                      gpu::readTextureRgba16Float(
                                          renderer.context(),
                                          renderer.passTexture(render::PassImage::DepthAndId)));
                }
                const std::vector<float>& wide = kind == batch::ViewImage::Hdr ? hdr : *depthAndId;
                for (std::uint32_t strip = 0; strip < count; ++strip) {
                    const batch::FloatStrip pixels{wide, layout.targetWidth(), strip, layout.width,
                                                   layout.height};
                    if (kind == batch::ViewImage::Hdr) {
                        passes[k].floats.push_back(batch::hdrPixels(pixels));
                    } else if (kind == batch::ViewImage::Depth) {
                        passes[k].floats.push_back(depthValues(
                            pixels, conventions, unitsPerModelUnit, views[first + strip]));
                    } else {
                        const image::ImageGray16 ids = batch::segmentationIdsOfPassTarget(pixels);
                        passes[k].floats.emplace_back(ids.pixels.begin(), ids.pixels.end());
                    }
                }
                continue;
            }
            image::ImageRgba8 wide;
            if (kind == batch::ViewImage::Color) {
                ENCORE_TRY_ASSIGN(wide, renderer.readImage());
            } else {
                ENCORE_TRY_ASSIGN(wide,
                                  gpu::readTexture(renderer.context(),
                                                   renderer.passTexture(batch::passImageOf(kind))));
            }
            for (std::uint32_t strip = 0; strip < count; ++strip) {
                image::ImageRgba8 view = batch::cropStrip(wide, strip, layout.width);
                // Linear values that the sRGB image encoded, as renderStrips decodes them.
                if (kind == batch::ViewImage::Normal || kind == batch::ViewImage::Material) {
                    batch::decodeNormalImage(view);
                }
                passes[k].rgba.push_back(std::move(view));
            }
        }
    }
    return passes;
}

}  // namespace

Result<std::vector<PassImages>> renderPasses(render::Renderer& renderer,
                                             const scene::Bounds& bounds,
                                             std::span<const batch::ViewCamera> views,
                                             const batch::ViewRigOptions& rig,
                                             const batch::StripLayout& layout,
                                             std::span<const batch::ViewImage> kinds,
                                             batch::SegmentationBy by,
                                             const PassConventions& conventions) {
    if (renderer.passTexture(render::PassImage::DepthAndId)) {
        return renderPassTargets(renderer, bounds, views, rig, layout, kinds, conventions);
    }
    batch::ExtraImages extras;
    applyPassKinds(kinds, conventions, extras);
    const glm::mat4 toUnitBox = batch::normalization(bounds, rig.normalize);
    // What the batch's writer makes of a float read-back of view `view` (ModelWriter's
    // floatEncoder, before encoding).
    const auto values = [&](batch::ViewImage kind) {
        return [&, kind](const batch::FloatStrip& pixels, std::uint32_t view) {
            if (kind == batch::ViewImage::Depth) {
                return depthValues(pixels, conventions, toUnitBox[0][0], views[view]);
            }
            if (kind == batch::ViewImage::Normal) {
                return batch::normalVectors(
                    pixels, batch::normalRotation(views[view], conventions.normalSpace,
                                                  conventions.camera));
            }
            return batch::objectCoordinates(pixels, toUnitBox);
        };
    };
    std::vector<PassImages> passes;
    for (const batch::ViewImage kind : kinds) {
        PassImages images;
        if (kind == batch::ViewImage::Depth || kind == batch::ViewImage::Coordinates ||
            (kind == batch::ViewImage::Normal && extras.normalsAsFloats())) {
            ENCORE_TRY_ASSIGN(images.floats, batch::renderChannelStrips(
                                                 renderer, bounds, views, rig, layout,
                                                 batch::passChannel(kind, extras), values(kind)));
        } else if (kind == batch::ViewImage::Hdr || kind == batch::ViewImage::Segmentation) {
            ENCORE_TRY_ASSIGN(images.floats, batch::renderFloatStrips(renderer, bounds, views, rig,
                                                                      layout, kind, by));
        } else {
            ENCORE_TRY_ASSIGN(images.rgba,
                              batch::renderStrips(renderer, bounds, views, rig, layout, kind));
        }
        passes.push_back(std::move(images));
    }
    return passes;
}

}  // namespace encore::python
