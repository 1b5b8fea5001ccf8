#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "CameraOptions.h"
#include "Commands.h"
#include "ShadingOptions.h"
#include "encore/gpu/Context.h"
#include "encore/render/Renderer.h"
#include "encore/scene/SceneData.h"

namespace encore::app {

namespace {

struct RenderOptions {
    std::string model;
    std::string output = "encore.png";
    std::string strategy = "bundles";
    std::uint32_t width = 1280;
    std::uint32_t height = 720;
    std::uint32_t samples = 4;
    float yawDegrees = 0.0f;
    std::uint32_t views = 1;
    bool strict = false;
    ShadingOptions shading;
    CameraOptions camera;
};

// Views side by side: each camera frames the scene for its strip, turned a few degrees from the
// previous one (two views: a stereo pair).
std::vector<render::Camera> viewCameras(const scene::Bounds& bounds, float aspect,
                                        float yawDegrees, std::uint32_t views) {
    constexpr float kViewSeparationDegrees = 4.0f;
    std::vector<render::Camera> cameras;
    for (std::uint32_t view = 0; view < views; ++view) {
        const float offset = (float(view) - 0.5f * float(views - 1)) * kViewSeparationDegrees;
        cameras.push_back(render::Camera::framing(bounds, aspect,
                                                  (yawDegrees + offset) * float(M_PI) / 180.0f));
    }
    return cameras;
}

int runRender(const RenderOptions& options, const GlobalOptions& global) {
    const auto kind = render::strategyFromName(options.strategy);
    if (!kind) {
        return reportError(makeError(ErrorCode::InvalidArgument,
                                     "Unknown strategy '" + options.strategy + "'."));
    }
    scene::LoadOptions loadOptions;
    loadOptions.strict = options.strict;
    auto scene = loadModel(options.model, loadOptions);
    if (!scene) {
        return reportError(scene.error());
    }
    auto context = createContext(global);
    if (!context) {
        return reportError(context.error());
    }

    render::RendererOptions rendererOptions;
    rendererOptions.target = {options.width, options.height, options.samples};
    if (auto shading = applyShadingOptions(options.shading, rendererOptions); !shading) {
        return reportError(shading.error());
    }
    auto renderer = render::Renderer::create(*context, rendererOptions);
    if (!renderer) {
        return reportError(renderer.error());
    }
    if (auto prepared = renderer->prepare(*scene, *kind); !prepared) {
        return reportError(prepared.error());
    }
    injectFaultsForTests(*context);
    // With several views each strip keeps the proportions of width / views by height.
    const float aspect = renderer->target().aspect() / float(options.views);
    std::vector<render::Camera> cameras;
    const bool explicitCamera = !options.camera.camera.empty() || options.camera.position;
    if (options.views > 1 && explicitCamera) {
        return reportError(makeError(ErrorCode::InvalidArgument,
                                     "--views frames the scene itself; it cannot be combined "
                                     "with --camera or --camera-position."));
    }
    if (options.views > 1) {
        cameras = viewCameras(scene->bounds, aspect, options.yawDegrees, options.views);
    } else {
        CameraOptions cameraOptions = options.camera;
        cameraOptions.yawDegrees = options.yawDegrees;
        auto camera = resolveCamera(cameraOptions, *scene, aspect);
        if (!camera) {
            return reportError(camera.error());
        }
        cameras.push_back(*camera);
    }
    const auto frame = renderer->renderViews(cameras);
    auto image = renderer->readImage();
    if (!image) {
        return reportError(image.error());
    }
    if (auto written = image::writePng(options.output, *image); !written) {
        return reportError(written.error());
    }
    if (global.verbose) {
        std::fprintf(stderr,
                     "strategy %s: %llu draws and %llu executeBundles in the frame, %llu draws in "
                     "bundles, %llu triangles, encode %.3f ms\n",
                     options.strategy.c_str(),
                     static_cast<unsigned long long>(frame.counters.drawCalls()),
                     static_cast<unsigned long long>(frame.counters.executeBundles),
                     static_cast<unsigned long long>(frame.bundleContents.drawCalls()),
                     static_cast<unsigned long long>(frame.counters.triangles +
                                                     frame.bundleContents.triangles),
                     frame.encodeMilliseconds);
        std::fprintf(stderr, "environment: image-based lighting maps built in %.0f ms\n",
                     renderer->lighting().environment().lastBuildMilliseconds());
    }
    std::printf("%s\n", options.output.c_str());
    return kExitOk;
}

}  // namespace

void addRenderCommand(CLI::App& app, const GlobalOptions& global, int& exitCode) {
    auto options = std::make_shared<RenderOptions>();
    auto* command = app.add_subcommand(
        "render", "Render a glTF 2.0 model (.gltf or .glb) headless into a PNG image.");
    command->add_option("model", options->model, "The .gltf or .glb file")->required();
    command->add_option("-o,--output", options->output, "The PNG to write")
        ->capture_default_str();
    command->add_option("-s,--strategy", options->strategy, "Rendering strategy")
        ->capture_default_str();
    command->add_option("--width", options->width, "Image width in pixels")
        ->capture_default_str()
        ->check(CLI::Range(1, 8192));
    command->add_option("--height", options->height, "Image height in pixels")
        ->capture_default_str()
        ->check(CLI::Range(1, 8192));
    command->add_option("--samples", options->samples, "Multisampling: 1 or 4")
        ->capture_default_str()
        ->check(CLI::IsMember({1, 4}));
    command->add_option("--yaw", options->yawDegrees,
                        "Turn the framing viewpoint around the model (degrees)");
    command->add_option("--views", options->views,
                        "Render N views side by side from one recording (2: stereo; bundle "
                        "strategies replay the same bundle per view)")
        ->capture_default_str()
        ->check(CLI::Range(1, 8));
    command->add_flag("--strict", options->strict,
                      "Treat warnings (missing images, unsupported optional features) as errors");
    addShadingOptions(*command, options->shading);
    addCameraOptions(*command, options->camera);
    command->callback([options, &global, &exitCode] { exitCode = runRender(*options, global); });
}

}  // namespace encore::app
