#include "Renderer.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <utility>

#include "BatchArguments.h"
#include "ModuleErrors.h"
#include "batch/CameraConvention.h"
#include "batch/ModelSeed.h"
#include "batch/OptionNames.h"
#include "batch/PointCloud.h"
#include "batch/PoseFile.h"
#include "batch/TransformsJson.h"
#include "batch/ViewStrips.h"
#include "encore/scene/SceneData.h"
#include "render/visibility/VisibilityFeatures.h"

namespace encore::python {
namespace {

// ENCORE_DEVICE, as `encore --device` reads it: how a Dask worker (encore.dask) is given its
// GPU. Unset or empty: 0.
std::size_t deviceFromEnvironment() {
    const char* variable = std::getenv("ENCORE_DEVICE");
    if (!variable || !*variable) {
        return 0;
    }
    char* end = nullptr;
    const unsigned long long index = std::strtoull(variable, &end, 10);
    if (*end != '\0' || variable[0] == '-') {
        throw py::value_error(std::string("ENCORE_DEVICE='") + variable +
                              "' is not a device index (0, 1, ...: encore.adapters() lists them)");
    }
    return std::size_t(index);
}

// The points `encore batch --point-cloud` writes to points.ply for the model named `name`: a
// dict of positions and normals, float32 (P, 3), and colours, uint8 (P, 4).
py::dict pointCloudArrays(const scene::SceneData& scene,
                          const batch::ViewRigOptions& rig,
                          const std::string& name,
                          std::uint32_t count) {
    const std::vector<batch::SurfacePoint> points =
        batch::samplePointCloud(scene, batch::normalization(scene.bounds, rig.normalize), count,
                                batch::modelSeed(rig.seed, name));
    py::array_t<float> positions({points.size(), std::size_t(3)});
    py::array_t<float> normals({points.size(), std::size_t(3)});
    py::array_t<std::uint8_t> colors({points.size(), std::size_t(4)});
    float* position = positions.mutable_data();
    float* normal = normals.mutable_data();
    std::uint8_t* color = colors.mutable_data();
    for (const batch::SurfacePoint& point : points) {
        for (int i = 0; i < 3; ++i) {
            *position++ = point.position[i];
            *normal++ = point.normal[i];
        }
        for (int i = 0; i < 4; ++i) {
            *color++ = point.color[i];
        }
    }
    py::dict cloud;
    cloud["positions"] = positions;
    cloud["normals"] = normals;
    cloud["colors"] = colors;
    return cloud;
}

}  // namespace

Renderer::Renderer(std::uint32_t samples,
                   std::optional<std::size_t> device,
                   const std::optional<std::string>& strategy)
    : mSamples(samples) {
    if (samples != 1 && samples != 4) {
        throw py::value_error("samples must be 1 or 4");
    }
    mAutoStrategy = strategy && *strategy == "auto";
    if (strategy && !mAutoStrategy) {
        mStrategy = render::strategyChoiceFromName(*strategy);
        if (!mStrategy) {
            std::string names;
            for (render::StrategyKind kind : render::allStrategies()) {
                names += (names.empty() ? "" : ", ") + std::string(render::strategyName(kind));
            }
            throw py::value_error("strategy '" + *strategy +
                                  "' is not one of Encore's strategies (" + names +
                                  "; a direct one may take +bundle; or auto)");
        }
    }
    gpu::ContextOptions options;
    options.adapterIndex = device ? *device : deviceFromEnvironment();
    render::requestVisibilityFeatures(options);
    mContext = std::make_unique<gpu::Context>(valueOrThrow(gpu::Context::create(options)));
    mBatchRenderers = std::make_unique<batch::BatchRenderer>(*mContext);
}

Scene Renderer::load(const std::string& path, bool allowUrisOutside) {
    Result<scene::SceneData> loaded = makeError(ErrorCode::InvalidArgument, "");
    {
        py::gil_scoped_release release;
        scene::LoadOptions options;
        options.allowUrisOutside = allowUrisOutside;
        // The triangles in the order `encore batch` loads them (BatchRun): the same pictures
        // either way, and the same points drawn for point_cloud, which follow that order.
        options.vertexCacheOrder = scene::VertexCacheOrder::Fast;
        loaded = scene::loadScene(path, options);
    }
    if (!loaded) {
        throw LoadError(loaded.error().message);
    }
    return Scene{std::make_shared<const scene::SceneData>(std::move(*loaded))};
}

py::object Renderer::renderViews(const Scene& scene,
                                 std::uint32_t views,
                                 const py::object& size,
                                 float elevation,
                                 float distance,
                                 std::optional<float> fov,
                                 bool random,
                                 std::uint64_t seed,
                                 bool normalize,
                                 bool normals,
                                 bool depth,
                                 const std::string& name,
                                 const py::object& variantName,
                                 const py::object& passes,
                                 const std::string& segmentation,
                                 const py::object& environment,
                                 float intensity,
                                 float rotation,
                                 float exposure,
                                 const std::string& toneMapping,
                                 const std::string& background,
                                 bool passFrames,
                                 const std::string& depthKind,
                                 const std::string& depthUnit,
                                 const std::string& normalSpace,
                                 const std::string& normalKind,
                                 const std::string& normalFormat,
                                 const std::optional<std::string>& cameraConvention,
                                 const std::optional<std::string>& distribution,
                                 const std::string& projection,
                                 float orthoScale,
                                 const py::object& azimuths,
                                 const py::object& elevations,
                                 const py::object& distances,
                                 const py::object& poses,
                                 std::uint32_t pointCloud) {
    const auto [width, height] = imageSize(size);
    const ViewShading shading =
        viewShading(environment, intensity, rotation, exposure, toneMapping, background);
    std::vector<batch::ViewImage> kinds;
    if (!passes.is_none()) {
        if (normals || depth) {
            throw py::value_error(
                "passes= replaces normals= and depth=: name \"normal\" and "
                "\"depth\" among the passes.");
        }
        kinds = passKinds(passes);
    }
    const batch::SegmentationBy by = segmentationBy(segmentation);
    const PassConventions conventions = passConventions(depthKind, depthUnit, normalSpace,
                                                        normalKind, normalFormat, cameraConvention);
    PassConventions cameraOnly;
    cameraOnly.camera = conventions.camera;
    if (passes.is_none() && !(conventions == cameraOnly)) {
        throw py::value_error(
            "depth_kind, depth_unit, normal_space, normal_kind and normal_format apply to "
            "passes=: name \"depth\" or \"normal\" among the passes.");
    }
    if (passes.is_none() && pointCloud > 0) {
        throw py::value_error(
            "point_cloud returns its points in the dict of passes=: give passes too.");
    }
    if (random && distribution) {
        throw py::value_error(
            "random=True draws the views on the sphere: give it or camera_distribution, not "
            "both.");
    }
    RigArguments arguments;
    arguments.views = views;
    arguments.elevation = elevation;
    arguments.distance = py::float_(distance);
    arguments.fov = fov ? py::object(py::float_(*fov)) : py::none();
    arguments.distribution =
        distribution ? named(batch::cameraDistributionNames(), *distribution, "camera_distribution")
        : random     ? batch::CameraDistribution::Sphere
                     : batch::CameraDistribution::Orbit;
    arguments.seed = seed;
    arguments.normalize = normalize;
    arguments.projection = named(batch::projectionNames(), projection, "projection");
    arguments.orthoScale = orthoScale;
    arguments.azimuths = azimuths;
    arguments.elevations = elevations;
    arguments.distances = distances;
    batch::ViewRigOptions rig = rigOptions(arguments);
    if (!poses.is_none()) {
        if (random || distribution || !azimuths.is_none() || !elevations.is_none() ||
            !distances.is_none()) {
            throw py::value_error(
                "poses= gives the cameras: random, camera_distribution, azimuths, elevations "
                "and distances place other ones.");
        }
        const std::string path = py::str(py::module_::import("os").attr("fspath")(poses));
        // Read in camera_convention's axes when given, else in the file's own or its form's
        // default, as `encore batch --poses` reads it.
        const std::optional<batch::CameraConvention> axes =
            cameraConvention ? std::optional(conventions.camera) : std::nullopt;
        auto read = batch::readPoseFile(path, "poses", axes, rig);
        if (!read) {
            throw py::value_error(read.error().message);
        }
        rig.poses = std::move(*read);
        rig.posesFile = path;
    }
    const std::vector<batch::ViewCamera> cameraViews = batch::viewCameras(rig, name);
    const std::size_t viewCount = cameraViews.size();  // The lists' length, if they give one.
    std::optional<scene::VariantId> variant;
    if (const std::string chosen = variantArgument(variantName); !chosen.empty()) {
        auto found = scene::resolveVariant(*scene.data, chosen);
        if (!found) {
            throw py::value_error(found.error().message);
        }
        variant = *found;
    }
    Rendered rendered;
    {
        py::gil_scoped_release release;
        std::lock_guard lock(mMutex);  // Python threads may share a renderer.
        rendered =
            valueOrThrow(render(scene.data, variant, cameraViews, rig, width, height, normals,
                                depth, shading, kinds, by, conventions, passFrames));
    }
    const auto rgbaArray = [&](const std::vector<image::ImageRgba8>& images) {
        py::array_t<std::uint8_t> pixels(
            {viewCount, std::size_t(height), std::size_t(width), std::size_t(4)});
        std::uint8_t* out = pixels.mutable_data();
        for (const image::ImageRgba8& image : images) {
            std::memcpy(out, image.pixels.data(), image.pixels.size());
            out += image.pixels.size();
        }
        return pixels;
    };
    py::array_t<std::uint8_t> pixels = rgbaArray(rendered.color);
    // The first view's (a pose file's may differ from the rig's).
    const batch::ViewCamera& first = cameraViews.front();
    batch::PinholeIntrinsics pinhole =
        batch::intrinsicsFor(width, height, first.horizontalFovRadians);
    if (first.projection == batch::Projection::Orthographic) {
        // Pixels per unit of the normalised world in place of the focal lengths: the same matrix
        // takes a point's camera x and y (OpenCV's axes) to its pixel, without the division.
        const glm::vec2 half =
            batch::orthographicHalfExtent(first.orthoScale, float(width) / height);
        pinhole.focalX = 0.5 * double(width) / double(half.x);
        pinhole.focalY = 0.5 * double(height) / double(half.y);
    }
    py::array_t<double> intrinsics({3, 3});
    auto k = intrinsics.mutable_unchecked<2>();
    const double values[3][3] = {{pinhole.focalX, 0.0, pinhole.centerX},
                                 {0.0, pinhole.focalY, pinhole.centerY},
                                 {0.0, 0.0, 1.0}};
    for (int row = 0; row < 3; ++row) {
        for (int column = 0; column < 3; ++column) {
            k(row, column) = values[row][column];
        }
    }
    py::array_t<double> cameras({viewCount, std::size_t(4), std::size_t(4)});
    auto c = cameras.mutable_unchecked<3>();
    for (std::size_t view = 0; view < cameraViews.size(); ++view) {
        // As transforms.json writes them (OpenGL: the matrix itself).
        const glm::dmat4 cameraToWorld =
            batch::cameraToWorldIn(cameraViews[view].cameraToWorld, conventions.camera);
        for (int row = 0; row < 4; ++row) {
            for (int column = 0; column < 4; ++column) {
                c(view, row, column) = cameraToWorld[column][row];  // glm: [column][row]
            }
        }
    }
    if (!passes.is_none()) {
        py::dict arrays;
        for (std::size_t i = 0; i < kinds.size(); ++i) {
            arrays[passName(kinds[i])] =
                passArray(kinds[i], rendered.passes[i], width, height, conventions.normalFormat);
        }
        arrays["intrinsics"] = intrinsics;
        arrays["cameras"] = cameras;
        if (pointCloud > 0) {
            arrays["point_cloud"] = pointCloudArrays(*scene.data, rig, name, pointCloud);
        }
        return arrays;
    }
    py::list result;
    result.append(pixels);
    result.append(intrinsics);
    result.append(cameras);
    if (normals) {
        result.append(rgbaArray(rendered.normals));
    }
    if (depth) {
        // The 16-bit values of 000_depth.png times its depth_scale: distances along the
        // camera axis in the cameras' units, 0 where the pixel is mostly empty.
        const double scale = batch::depthScale(rig);
        py::array_t<float> depthArray({viewCount, std::size_t(height), std::size_t(width)});
        float* out = depthArray.mutable_data();
        for (const image::ImageGray16& image : rendered.depth) {
            for (const std::uint16_t steps : image.pixels) {
                *out++ = float(double(steps) * scale);
            }
        }
        result.append(depthArray);
    }
    return py::tuple(result);
}

batch::BatchRendererCounts Renderer::batchCounts() {
    // Without the GIL while waiting: a batch on another thread takes it to report progress.
    py::gil_scoped_release release;
    std::lock_guard lock(mMutex);
    return mBatchRenderers->counts();
}

Result<Renderer::Rendered> Renderer::render(const std::shared_ptr<const scene::SceneData>& scene,
                                            std::optional<scene::VariantId> variant,
                                            const std::vector<batch::ViewCamera>& views,
                                            const batch::ViewRigOptions& rig,
                                            std::uint32_t width,
                                            std::uint32_t height,
                                            bool normals,
                                            bool depth,
                                            const ViewShading& shading,
                                            std::span<const batch::ViewImage> kinds,
                                            batch::SegmentationBy by,
                                            const PassConventions& conventions,
                                            bool passFrames) {
    const batch::StripLayout layout =
        batch::stripLayout(width, height, std::uint32_t(views.size()), mContext->limits());
    const render::StrategyChoice choice =
        mStrategy.value_or(render::StrategyChoice::of(render::StrategyKind::Bundles, false));
    // The passes that share the colour's camera are drawn in its render pass, as `encore
    // batch` draws them, unless pass_frames=True.
    batch::ExtraImages images;
    applyPassKinds(kinds, conventions, images);
    images.drawing = passFrames ? batch::PassDrawing::Frames : batch::PassDrawing::Targets;
    const render::PassTargets passTargets =
        batch::drawsPassTargets(images, choice.kind, mContext->limits())
            ? batch::passTargetsFor(by)
            : render::PassTargets::None;
    // Ids from one sample of each pixel, the colour antialiased (render/SampleIdPass.h).
    const bool exactIds = images.segmentation && mSamples > 1;
    if (!mRenderer || mRenderer->target().width() != layout.targetWidth() ||
        mRenderer->target().height() != layout.height || mPassTargets != passTargets ||
        mRenderer->target().options().exactIds != exactIds) {
        render::RendererOptions options;
        options.passTargets = passTargets;
        mPassTargets = passTargets;
        options.target = {layout.targetWidth(), layout.height, mSamples};
        options.target.exactIds = exactIds;
        options.toneMapping.background = render::BackgroundKind::Transparent;
        options.target.hdr = true;  // Whatever the background: depth and HDR read it.
        options.keepPipelines = true;
        mRenderer.reset();
        ENCORE_TRY_ASSIGN(auto created, render::Renderer::create(*mContext, options));
        mRenderer = std::make_unique<render::Renderer>(std::move(created));
        mPrepared.reset();
        mEnvironment.clear();  // A new renderer lights with the studio environment.
    }
    if (mPrepared != scene) {
        // The renderer refers to the scene it was given until the next prepare, even when
        // preparing failed: hold it that long.
        mPrepared.reset();
        mHeld = scene;
        ENCORE_TRY(mRenderer->prepare(*scene, choice.kind, choice.bundle));
        mPrepared = scene;
    }
    // Only material bindings change between variants: the prepared scene stays.
    ENCORE_TRY(mRenderer->selectVariant(variant));
    ENCORE_TRY(applyShading(*mRenderer, shading, mEnvironment));
    Rendered rendered;
    if (!kinds.empty()) {
        ENCORE_TRY_ASSIGN(rendered.passes, renderPasses(*mRenderer, scene->bounds, views, rig,
                                                        layout, kinds, by, conventions));
    }
    // With passes, the colour is its "rgba" pass.
    const bool colorPass = kinds.empty();
    if (colorPass) {
        ENCORE_TRY_ASSIGN(rendered.color,
                          batch::renderStrips(*mRenderer, scene->bounds, views, rig, layout));
    }
    if (normals) {
        ENCORE_TRY_ASSIGN(rendered.normals,
                          batch::renderStrips(*mRenderer, scene->bounds, views, rig, layout,
                                              batch::ViewImage::Normal));
    }
    if (depth) {
        ENCORE_TRY_ASSIGN(rendered.depth,
                          batch::renderDepthStrips(*mRenderer, scene->bounds, views, rig, layout));
    }
    ENCORE_TRY(mContext->checkNoErrors("Rendering '" + scene->sourcePath.string() + "'"));
    return rendered;
}

}  // namespace encore::python
