#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "CameraOptions.h"
#include "Commands.h"
#include "CullingFlags.h"
#include "ShadingOptions.h"
#include "StrategyOptions.h"
#include "encore/gpu/Context.h"
#include "encore/render/Renderer.h"
#include "encore/scene/AnimationPlayer.h"
#include "encore/scene/SceneData.h"

namespace encore::app {

namespace {

struct RenderOptions {
    std::string model;
    std::string output = "encore.png";
    std::string strategy = "bundles";
    bool bundle = false;  // --bundle: the strategy's frame recorded once into render bundles.
    std::uint32_t width = 1280;
    std::uint32_t height = 720;
    std::uint32_t samples = 4;
    float yawDegrees = 0.0f;
    std::uint32_t views = 1;
    bool strict = false;
    std::optional<double> time;   // --time: animation time in seconds.
    std::string animation;        // --animation N|NAME (all when empty).
    std::string frames;           // --frames START:END:STEP.
    std::string animate = "cpu";  // --animate cpu|gpu.
    std::string variant;          // --variant N|NAME (KHR_materials_variants; default when empty).
    ShadingOptions shading;
    CameraOptions camera;
    render::CullingOptions culling;
};

// Views side by side: each camera frames the scene for its strip, turned a few degrees from the
// previous one (two views: a stereo pair).
std::vector<render::Camera> viewCameras(const scene::Bounds& bounds,
                                        float aspect,
                                        float yawDegrees,
                                        std::uint32_t views) {
    constexpr float kViewSeparationDegrees = 4.0f;
    std::vector<render::Camera> cameras;
    for (std::uint32_t view = 0; view < views; ++view) {
        const float offset = (float(view) - 0.5f * float(views - 1)) * kViewSeparationDegrees;
        cameras.push_back(
            render::Camera::framing(bounds, aspect, (yawDegrees + offset) * float(M_PI) / 180.0f));
    }
    return cameras;
}

// The animation times of `--frames START:END:STEP`: START, START + STEP, ... up to END
// (inclusive, within a thousandth of a step).
Result<std::vector<double>> parseFrames(const std::string& text) {
    auto invalid = [&](const std::string& why) {
        return makeError(ErrorCode::InvalidArgument,
                         "--frames takes START:END:STEP in seconds ('" + text + "'): " + why);
    };
    double values[3] = {};
    std::size_t begin = 0;
    for (int i = 0; i < 3; ++i) {
        const std::size_t end = i < 2 ? text.find(':', begin) : text.size();
        if (end == std::string::npos) {
            return invalid("expected three numbers separated by ':'.");
        }
        const std::string part = text.substr(begin, end - begin);
        char* stop = nullptr;
        values[i] = std::strtod(part.c_str(), &stop);
        if (part.empty() || stop != part.c_str() + part.size() || !std::isfinite(values[i])) {
            return invalid("'" + part + "' is not a number.");
        }
        begin = end + 1;
    }
    const auto [start, end, step] = values;
    if (step <= 0.0) {
        return invalid("STEP must be positive.");
    }
    if (end < start) {
        return invalid("END must not be before START.");
    }
    const double count = std::floor((end - start) / step + 1e-3) + 1.0;
    constexpr double kMaxFrames = 100000.0;
    if (count > kMaxFrames) {
        return invalid("more than 100000 frames.");
    }
    std::vector<double> times;
    for (std::size_t i = 0; i < static_cast<std::size_t>(count); ++i) {
        times.push_back(start + double(i) * step);
    }
    return times;
}

// `pattern` with its one printf-style integer conversion (%d, %4d, %04d) replaced by `index`.
Result<std::string> framePath(const std::string& pattern, std::size_t index) {
    const std::size_t percent = pattern.find('%');
    auto invalid = [&] {
        return makeError(ErrorCode::InvalidArgument,
                         "With --frames, -o needs one integer conversion such as %04d for the "
                         "frame number ('" +
                             pattern + "').");
    };
    if (percent == std::string::npos) {
        return invalid();
    }
    std::size_t end = percent + 1;
    while (end < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[end]))) {
        ++end;
    }
    if (end >= pattern.size() || pattern[end] != 'd' || end - percent > 4 ||
        pattern.find('%', end) != std::string::npos) {
        return invalid();
    }
    char number[32];
    const std::string conversion = pattern.substr(percent, end - percent + 1);
    std::snprintf(number, sizeof(number), conversion.c_str(), static_cast<int>(index));
    return pattern.substr(0, percent) + number + pattern.substr(end + 1);
}

// Animation times: none (the rest pose), --time, or every frame of --frames.
Result<std::vector<double>> animationTimes(const RenderOptions& options) {
    std::vector<double> times;
    if (!options.frames.empty()) {
        if (options.time) {
            return makeError(ErrorCode::InvalidArgument, "--time and --frames cannot be combined.");
        }
        ENCORE_TRY_ASSIGN(times, parseFrames(options.frames));
        ENCORE_TRY(framePath(options.output, 0));
    } else if (options.time) {
        if (!std::isfinite(*options.time)) {
            return makeError(ErrorCode::InvalidArgument,
                             "--time must be a finite number of seconds.");
        }
        times.push_back(*options.time);
    }
    return times;
}

// A renderer with `scene` prepared, in the variant and animation the options name.
Result<render::Renderer> preparedRenderer(gpu::Context& context,
                                          const RenderOptions& options,
                                          const scene::SceneData& scene,
                                          const render::StrategyChoice& strategy) {
    std::optional<scene::VariantId> variant;
    if (!options.variant.empty()) {
        ENCORE_TRY_ASSIGN(variant, scene::resolveVariant(scene, options.variant));
    }
    render::RendererOptions rendererOptions;
    rendererOptions.target = {options.width, options.height, options.samples};
    rendererOptions.animation = *render::animationEvaluationFromName(options.animate);
    rendererOptions.culling = options.culling;
    ENCORE_TRY(applyShadingOptions(options.shading, rendererOptions));
    ENCORE_TRY_ASSIGN(auto renderer, render::Renderer::create(context, rendererOptions));
    ENCORE_TRY(renderer.prepare(scene, strategy.kind, strategy.bundle));
    ENCORE_TRY(renderer.selectVariant(variant));
    if (!options.animation.empty()) {
        if (!scene::findAnimation(scene, options.animation)) {
            return makeError(ErrorCode::InvalidArgument,
                             "'" + options.model + "' has no animation '" + options.animation +
                                 "' (it has " + std::to_string(scene.animations.size()) +
                                 "; give a name or an index).");
        }
        ENCORE_TRY(renderer.selectAnimation(options.animation));
    }
    return renderer;
}

// The frame's cameras: --views framing the scene side by side, or the one camera asked for.
Result<std::vector<render::Camera>> frameCameras(const RenderOptions& options,
                                                 const scene::SceneData& scene,
                                                 const render::Renderer& renderer) {
    // With several views each strip keeps the proportions of width / views by height.
    const float aspect = renderer.target().aspect() / float(options.views);
    const bool explicitCamera = !options.camera.camera.empty() || options.camera.position;
    if (options.views > 1 && explicitCamera) {
        return makeError(ErrorCode::InvalidArgument,
                         "--views frames the scene itself; it cannot be combined with --camera "
                         "or --camera-position.");
    }
    if (options.views > 1) {
        return viewCameras(scene.bounds, aspect, options.yawDegrees, options.views);
    }
    CameraOptions cameraOptions = options.camera;
    cameraOptions.yawDegrees = options.yawDegrees;
    ENCORE_TRY_ASSIGN(auto camera, resolveCamera(cameraOptions, scene, aspect));
    return std::vector<render::Camera>{camera};
}

// Draws and writes a frame per animation time (one for none): the last frame's result and the
// paths written.
Result<std::pair<render::FrameResult, std::vector<std::string>>> renderFrames(
    render::Renderer& renderer,
    const RenderOptions& options,
    std::span<const render::Camera> cameras,
    const std::vector<double>& times) {
    // One prepared renderer (bundle strategies: one recording) for every frame; animation
    // changes only buffer contents.
    render::FrameResult frame;
    std::vector<std::string> written;
    const std::size_t frameCount = std::max<std::size_t>(times.size(), 1);
    for (std::size_t index = 0; index < frameCount; ++index) {
        if (!times.empty()) {
            ENCORE_TRY(renderer.setAnimationTime(times[index]));
        }
        frame = renderer.renderViews(cameras);
        ENCORE_TRY_ASSIGN(auto image, renderer.readImage());
        std::string path = options.output;
        if (!options.frames.empty()) {
            path = *framePath(options.output, index);
        }
        ENCORE_TRY(image::writePng(path, image));
        written.push_back(std::move(path));
    }
    return std::pair{frame, std::move(written)};
}

// -v: what the last frame did.
void printFrameDetails(const render::Renderer& renderer,
                       const render::FrameResult& frame,
                       const render::StrategyChoice& strategy,
                       bool animated) {
    const render::AnimationFrameStats& animation = renderer.animationStats();
    if (animated && renderer.animationEvaluation() == render::AnimationEvaluation::Gpu) {
        std::fprintf(stderr,
                     "animation on the GPU (last frame): %u compute dispatches, %u buffer copies, "
                     "%llu bytes written\n",
                     animation.gpu.dispatches, animation.gpu.copies,
                     static_cast<unsigned long long>(animation.bytesWritten));
    } else if (animated) {
        std::fprintf(stderr,
                     "animation (last frame): %u channels evaluated, %u instances, %u joints, "
                     "%u morph weights, %llu bytes written\n",
                     animation.player.channelsEvaluated, animation.instancesWritten,
                     animation.upload.jointsWritten, animation.upload.weightsWritten,
                     static_cast<unsigned long long>(animation.bytesWritten));
    }
    std::fprintf(
        stderr,
        "strategy %s: %llu draws and %llu executeBundles in the frame, %llu draws in "
        "bundles, %llu triangles, encode %.3f ms\n",
        render::strategyChoiceName(strategy).c_str(),
        static_cast<unsigned long long>(frame.counters.drawCalls()),
        static_cast<unsigned long long>(frame.counters.executeBundles),
        static_cast<unsigned long long>(frame.bundleContents.drawCalls()),
        static_cast<unsigned long long>(frame.counters.triangles + frame.bundleContents.triangles),
        frame.encodeMilliseconds);
    std::fprintf(stderr, "environment: image-based lighting maps built in %.0f ms\n",
                 renderer.stats().environmentBuildMilliseconds);
}

int runRender(const RenderOptions& options, const GlobalOptions& global) {
    const auto strategy = parseStrategyChoice(options.strategy, options.bundle);
    if (!strategy) {
        return reportError(strategy.error());
    }
    const auto times = animationTimes(options);
    if (!times) {
        return reportError(times.error());
    }
    scene::LoadOptions loadOptions;
    loadOptions.strict = options.strict;
    auto scene = loadModel(options.model, loadOptions, global);
    if (!scene) {
        return reportError(scene.error());
    }
    if (!options.variant.empty()) {
        // A variant the model lacks is bad input before any device starts.
        if (auto found = scene::resolveVariant(*scene, options.variant); !found) {
            return reportError(found.error());
        }
    }
    auto context = createContext(global);
    if (!context) {
        return reportError(context.error());
    }
    auto renderer = preparedRenderer(*context, options, *scene, *strategy);
    if (!renderer) {
        return reportError(renderer.error());
    }
    injectFaultsForTests(*context);
    const auto cameras = frameCameras(options, *scene, *renderer);
    if (!cameras) {
        return reportError(cameras.error());
    }
    const auto frames = renderFrames(*renderer, options, *cameras, *times);
    if (!frames) {
        return reportError(frames.error());
    }
    if (global.verbose) {
        printFrameDetails(*renderer, frames->first, *strategy, !times->empty());
    }
    for (const std::string& path : frames->second) {
        std::printf("%s\n", path.c_str());
    }
    return kExitOk;
}

}  // namespace

void addRenderCommand(CLI::App& app, const GlobalOptions& global, int& exitCode) {
    auto options = std::make_shared<RenderOptions>();
    auto* command = app.add_subcommand(
        "render", "Render a glTF 2.0 model (.gltf or .glb) headless into a PNG image.");
    command->add_option("model", options->model, "The .gltf or .glb file")->required();
    command->add_option("-o,--output", options->output, "The PNG to write")->capture_default_str();
    command->add_option("-s,--strategy", options->strategy, "Rendering strategy")
        ->capture_default_str();
    command->add_flag("--bundle", options->bundle,
                      "Record the strategy's frame once into render bundles and replay them "
                      "(materials and gpu-culling become bundles and gpu-culling-bundles)");
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
    command
        ->add_option("--views", options->views,
                     "Render N views side by side from one recording (2: stereo; bundle "
                     "strategies replay the same bundle per view)")
        ->capture_default_str()
        ->check(CLI::Range(1, 8));
    command->add_flag("--strict", options->strict,
                      "Treat warnings (missing images, unsupported optional features) as errors");
    command->add_option("--time", options->time,
                        "Animation time in seconds (all animations, or --animation's)");
    command->add_option("--animation", options->animation,
                        "Play only this animation: its index or its name");
    command
        ->add_option("--animate", options->animate,
                     "Evaluate animation on the cpu (default) or the gpu (compute passes "
                     "writing the same buffers)")
        ->check(CLI::IsMember({"cpu", "gpu"}));
    command->add_option("--variant", options->variant,
                        "Draw the materials of this KHR_materials_variants variant: its index or "
                        "its name (encore info lists them)");
    command->add_option("--frames", options->frames,
                        "Render an image sequence at times START:END:STEP (seconds) from one "
                        "recording; -o must hold a frame number conversion, e.g. "
                        "frame_%04d.png");
    addShadingOptions(*command, options->shading);
    addCameraOptions(*command, options->camera);
    addCullingOptions(*command, options->culling);
    command->callback([options, &global, &exitCode] { exitCode = runRender(*options, global); });
}

}  // namespace encore::app
