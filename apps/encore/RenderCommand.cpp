#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "CameraOptions.h"
#include "Commands.h"
#include "CullingFlags.h"
#include "ShadingOptions.h"
#include "StrategyOptions.h"
#include "encore/gpu/Context.h"
#include "encore/render/Renderer.h"
#include "encore/scene/AnimationPlayer.h"
#include "encore/scene/MaterialVariants.h"
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

int runRender(const RenderOptions& options, const GlobalOptions& global) {
    const auto strategy = parseStrategyChoice(options.strategy, options.bundle);
    if (!strategy) {
        return reportError(strategy.error());
    }
    // Animation times: none (the rest pose), --time, or every frame of --frames.
    std::vector<double> times;
    const bool sequence = !options.frames.empty();
    if (sequence) {
        if (options.time) {
            return reportError(
                makeError(ErrorCode::InvalidArgument, "--time and --frames cannot be combined."));
        }
        auto parsed = parseFrames(options.frames);
        if (!parsed) {
            return reportError(parsed.error());
        }
        times = std::move(*parsed);
        if (auto path = framePath(options.output, 0); !path) {
            return reportError(path.error());
        }
    } else if (options.time) {
        if (!std::isfinite(*options.time)) {
            return reportError(makeError(ErrorCode::InvalidArgument,
                                         "--time must be a finite number of seconds."));
        }
        times.push_back(*options.time);
    }
    scene::LoadOptions loadOptions;
    loadOptions.strict = options.strict;
    auto scene = loadModel(options.model, loadOptions, global);
    if (!scene) {
        return reportError(scene.error());
    }
    std::optional<scene::VariantId> variant;
    if (!options.variant.empty()) {
        auto found = scene::resolveVariant(*scene, options.variant);
        if (!found) {
            return reportError(found.error());
        }
        variant = *found;
    }
    auto context = createContext(global);
    if (!context) {
        return reportError(context.error());
    }

    render::RendererOptions rendererOptions;
    rendererOptions.target = {options.width, options.height, options.samples};
    rendererOptions.animation = *render::animationEvaluationFromName(options.animate);
    rendererOptions.culling = options.culling;
    if (auto shading = applyShadingOptions(options.shading, rendererOptions); !shading) {
        return reportError(shading.error());
    }
    auto renderer = render::Renderer::create(*context, rendererOptions);
    if (!renderer) {
        return reportError(renderer.error());
    }
    if (auto prepared = renderer->prepare(*scene, strategy->kind, strategy->bundle); !prepared) {
        return reportError(prepared.error());
    }
    if (auto selected = renderer->selectVariant(variant); !selected) {
        return reportError(selected.error());
    }
    if (!options.animation.empty()) {
        if (!scene::findAnimation(*scene, options.animation)) {
            return reportError(makeError(
                ErrorCode::InvalidArgument,
                "'" + options.model + "' has no animation '" + options.animation + "' (it has " +
                    std::to_string(scene->animations.size()) + "; give a name or an index)."));
        }
        if (auto selected = renderer->selectAnimation(options.animation); !selected) {
            return reportError(selected.error());
        }
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
    // One prepared renderer (bundle strategies: one recording) for every frame; animation
    // changes only buffer contents.
    render::FrameResult frame;
    std::vector<std::string> written;
    const std::size_t frameCount = std::max<std::size_t>(times.size(), 1);
    for (std::size_t index = 0; index < frameCount; ++index) {
        if (!times.empty()) {
            if (auto animated = renderer->setAnimationTime(times[index]); !animated) {
                return reportError(animated.error());
            }
        }
        frame = renderer->renderViews(cameras);
        auto image = renderer->readImage();
        if (!image) {
            return reportError(image.error());
        }
        std::string path = options.output;
        if (sequence) {
            path = *framePath(options.output, index);
        }
        if (auto saved = image::writePng(path, *image); !saved) {
            return reportError(saved.error());
        }
        written.push_back(std::move(path));
    }
    if (global.verbose && !times.empty() &&
        renderer->animationEvaluation() == render::AnimationEvaluation::Gpu) {
        const render::AnimationFrameStats& animation = renderer->animationStats();
        std::fprintf(stderr,
                     "animation on the GPU (last frame): %u compute dispatches, %u buffer copies, "
                     "%llu bytes written\n",
                     animation.gpu.dispatches, animation.gpu.copies,
                     static_cast<unsigned long long>(animation.bytesWritten));
    } else if (global.verbose && !times.empty()) {
        const render::AnimationFrameStats& animation = renderer->animationStats();
        std::fprintf(stderr,
                     "animation (last frame): %u channels evaluated, %u instances, %u joints, "
                     "%u morph weights, %llu bytes written\n",
                     animation.player.channelsEvaluated, animation.instancesWritten,
                     animation.upload.jointsWritten, animation.upload.weightsWritten,
                     static_cast<unsigned long long>(animation.bytesWritten));
    }
    if (global.verbose) {
        std::fprintf(stderr,
                     "strategy %s: %llu draws and %llu executeBundles in the frame, %llu draws in "
                     "bundles, %llu triangles, encode %.3f ms\n",
                     render::strategyChoiceName(*strategy).c_str(),
                     static_cast<unsigned long long>(frame.counters.drawCalls()),
                     static_cast<unsigned long long>(frame.counters.executeBundles),
                     static_cast<unsigned long long>(frame.bundleContents.drawCalls()),
                     static_cast<unsigned long long>(frame.counters.triangles +
                                                     frame.bundleContents.triangles),
                     frame.encodeMilliseconds);
        std::fprintf(stderr, "environment: image-based lighting maps built in %.0f ms\n",
                     renderer->lighting().environment().lastBuildMilliseconds());
    }
    for (const std::string& path : written) {
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
