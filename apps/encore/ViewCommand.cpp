#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "CameraOptions.h"
#include "Commands.h"
#include "CullingFlags.h"
#include "ShadingOptions.h"
#include "StrategyOptions.h"
#include "encore/scene/SceneData.h"
#include "render/Animometer.h"
#include "scene/SceneGenerator.h"
#include "view/ViewScript.h"
#include "view/Viewer.h"

namespace encore::app {

namespace {

struct ViewOptions {
    std::string model;
    std::optional<std::uint32_t> objects;     // --objects N: a generated scene.
    std::optional<std::uint32_t> animometer;  // --animometer N: the Animometer's triangles.
    std::string strategy = "bundles";
    bool bundle = false;
    std::uint32_t width = 1280;
    std::uint32_t height = 720;
    std::uint32_t samples = 4;
    bool uncapped = false;
    bool noOverlay = false;
    bool strict = false;
    std::string animation;
    std::string animate = "cpu";
    std::string variant;
    std::string script;
    std::optional<std::uint32_t> frames;  // --frames N [--screenshot out.png]: then exit.
    std::string screenshot;
    ShadingOptions shading;
    CameraOptions camera;
    render::CullingOptions culling;
};

// The options that exclude each other, and the script they make: --script's file, or --frames
// (and --screenshot) as one.
Result<std::optional<std::vector<view::ScriptStep>>> viewScript(const ViewOptions& options) {
    const int sources = int(!options.model.empty()) + int(options.objects.has_value()) +
                        int(options.animometer.has_value());
    if (sources != 1) {
        return makeError(ErrorCode::InvalidArgument,
                         "encore view shows one thing: a MODEL, --objects N or --animometer N.");
    }
    if (!options.screenshot.empty() && !options.frames) {
        return makeError(ErrorCode::InvalidArgument,
                         "--screenshot needs --frames N (how many frames to show before it is "
                         "taken).");
    }
    if (options.frames && !options.script.empty()) {
        return makeError(ErrorCode::InvalidArgument, "--frames and --script cannot be combined.");
    }
    if (!options.script.empty()) {
        ENCORE_TRY_ASSIGN(auto script, view::loadViewScript(options.script));
        return std::optional<std::vector<view::ScriptStep>>(std::move(script));
    }
    if (!options.frames) {
        return std::optional<std::vector<view::ScriptStep>>();
    }
    std::vector<view::ScriptStep> steps;
    view::ScriptStep frames;
    frames.command = view::ScriptCommand::Frames;
    frames.count = *options.frames;
    steps.push_back(frames);
    if (!options.screenshot.empty()) {
        view::ScriptStep screenshot;
        screenshot.command = view::ScriptCommand::Screenshot;
        screenshot.path = options.screenshot;
        steps.push_back(screenshot);
    }
    return std::optional<std::vector<view::ScriptStep>>(std::move(steps));
}

// The model, or a generated scene (none for the Animometer), checked against --animation and
// --variant before the window opens: a bad name is a usage error, named with what there is.
Result<std::unique_ptr<scene::SceneData>> viewedScene(const ViewOptions& options,
                                                      const scene::LoadOptions& loadOptions,
                                                      const GlobalOptions& global) {
    std::unique_ptr<scene::SceneData> scene;
    if (!options.model.empty()) {
        ENCORE_TRY_ASSIGN(auto loaded, loadModel(options.model, loadOptions, global));
        scene = std::make_unique<scene::SceneData>(std::move(loaded));
    } else if (options.objects) {
        scene::GeneratorOptions generator;
        generator.objectCount = *options.objects;
        ENCORE_TRY_ASSIGN(auto glb, scene::generateSceneGlb(generator));
        ENCORE_TRY_ASSIGN(
            auto loaded,
            scene::loadSceneFromMemory(
                glb, {}, "generated " + std::to_string(*options.objects) + " objects"));
        scene = std::make_unique<scene::SceneData>(std::move(loaded));
    }
    if (scene && !options.animation.empty() && !scene::findAnimation(*scene, options.animation)) {
        return makeError(ErrorCode::InvalidArgument,
                         "'" + options.model + "' has no animation '" + options.animation + "'.");
    }
    if (!options.variant.empty()) {
        if (!scene) {
            return makeError(ErrorCode::InvalidArgument,
                             "--variant needs a MODEL (a generated scene or the Animometer has no "
                             "material variants).");
        }
        ENCORE_TRY(scene::resolveVariant(*scene, options.variant));
    }
    return scene;
}

// The viewer's options from the command's (the script set before).
Result<void> fillViewerOptions(const ViewOptions& options,
                               const scene::LoadOptions& loadOptions,
                               const GlobalOptions& global,
                               const render::StrategyChoice& strategy,
                               view::ViewerOptions& viewer) {
    viewer.renderer.target = {options.width, options.height, options.samples};
    viewer.renderer.animation = *render::animationEvaluationFromName(options.animate);
    viewer.renderer.culling = options.culling;
    ENCORE_TRY(applyShadingOptions(options.shading, viewer.renderer));
    viewer.strategy = strategy.kind;
    viewer.bundle = strategy.bundle;
    if (options.animometer) {
        render::AnimometerOptions animometer;
        animometer.triangles = *options.animometer;
        animometer.bundle = options.bundle;
        viewer.animometer = animometer;
    }
    viewer.present =
        options.uncapped ? view::PresentPreference::Uncapped : view::PresentPreference::Vsync;
    viewer.overlay = !options.noOverlay;
    viewer.animation = options.animation;
    viewer.variant = options.variant;
    const CameraOptions cameraOptions = options.camera;
    viewer.initialCamera = [cameraOptions](const scene::SceneData& data, float aspect) {
        return resolveCamera(cameraOptions, data, aspect);
    };
    viewer.loadScene = [loadOptions, &global](const std::string& path) {
        return loadModel(path, loadOptions, global);
    };
    viewer.report = [](const std::string& line) {
        std::printf("%s\n", line.c_str());
        std::fflush(stdout);
    };
    return {};
}

int runView(const ViewOptions& options, const GlobalOptions& global) {
    auto script = viewScript(options);
    if (!script) {
        return reportError(script.error());
    }
    const auto strategy = parseStrategyChoice(options.strategy, options.bundle);
    if (!strategy) {
        return reportError(strategy.error());
    }
    scene::LoadOptions loadOptions;
    loadOptions.strict = options.strict;
    auto scene = viewedScene(options, loadOptions, global);
    if (!scene) {
        return reportError(scene.error());
    }
    // The window first: without a display nothing else is worth starting.
    auto window = view::Window::create("encore view", options.width, options.height);
    if (!window) {
        return reportError(window.error());
    }
    auto context = createContext(global, /*timestamps=*/true);
    if (!context) {
        return reportError(context.error());
    }
    view::ViewerOptions viewer;
    viewer.script = std::move(*script);
    if (auto filled = fillViewerOptions(options, loadOptions, global, *strategy, viewer); !filled) {
        return reportError(filled.error());
    }
    if (!viewer.script) {
        std::fprintf(stderr, "adapter: %s\n", context->adapterDescription().summary().c_str());
    }
    auto created = view::Viewer::create(*context, *window, std::move(*scene), std::move(viewer));
    if (!created) {
        return reportError(created.error());
    }
    if (auto ran = (*created)->run(); !ran) {
        return reportError(ran.error());
    }
    return kExitOk;
}

}  // namespace

void addViewCommand(CLI::App& app, const GlobalOptions& global, int& exitCode) {
    auto options = std::make_shared<ViewOptions>();
    auto* command = app.add_subcommand(
        "view",
        "Show a model, a generated scene or the Animometer in a window, live, with any "
        "strategy (needs a display; `encore render` works without one).");
    command->add_option("model", options->model, "The .gltf or .glb file");
    command->add_option("--objects", options->objects, "Show a generated scene of N objects")
        ->check(CLI::Range(1, 1000000));
    command
        ->add_option("--animometer", options->animometer,
                     "Show the Animometer scene with N triangles")
        ->check(CLI::Range(1u, render::kMaxAnimometerTriangles));
    command->add_option("-s,--strategy", options->strategy, "Rendering strategy (keys 1-8)")
        ->capture_default_str();
    command->add_flag("--bundle", options->bundle,
                      "Draw the strategy's frame from render bundles (key B)");
    command->add_option("--width", options->width, "Window width in pixels")
        ->capture_default_str()
        ->check(CLI::Range(1, 8192));
    command->add_option("--height", options->height, "Window height in pixels")
        ->capture_default_str()
        ->check(CLI::Range(1, 8192));
    command->add_option("--samples", options->samples, "Multisampling: 1 or 4")
        ->capture_default_str()
        ->check(CLI::IsMember({1, 4}));
    command->add_flag("--uncapped", options->uncapped,
                      "Present with the lowest-latency mode the surface supports instead of "
                      "waiting for the display (FIFO)");
    command->add_flag("--no-overlay", options->noOverlay, "Start with the overlay hidden (key O)");
    command->add_flag("--strict", options->strict,
                      "Treat warnings (missing images, unsupported optional features) as errors");
    command->add_option("--animation", options->animation,
                        "Play only this animation: its index or its name");
    command->add_option("--variant", options->variant,
                        "Show this KHR_materials_variants variant first: its index or its name "
                        "(key V cycles them)");
    command
        ->add_option("--animate", options->animate,
                     "Evaluate animation on the cpu (default) or the gpu")
        ->check(CLI::IsMember({"cpu", "gpu"}));
    command->add_option("--script", options->script,
                        "Run a scripted session (frames, keys, resizes, drops, screenshots; see "
                        "the README) and exit");
    command->add_option("--frames", options->frames, "Show N frames, then exit")
        ->check(CLI::Range(1, 100000));
    command->add_option("--screenshot", options->screenshot,
                        "With --frames: save the last frame as this PNG (without the overlay)");
    addShadingOptions(*command, options->shading);
    addCameraOptions(*command, options->camera);
    addCullingOptions(*command, options->culling);
    command->callback([options, &global, &exitCode] { exitCode = runView(*options, global); });
}

}  // namespace encore::app
