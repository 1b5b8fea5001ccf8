// The frame loop: each frame advances the animation, draws the scene, presents it with the
// overlay, saves the screenshots asked for and keeps the timings the overlay shows.

#include <chrono>

#include "encore/image/ImageCodec.h"
#include "gpu/Readback.h"
#include "view/ViewerState.h"

namespace encore::view {

Result<void> Viewer::State::renderFrame(double deltaSeconds) {
    if (!paused) {
        animationTime += deltaSeconds;
    }
    FrameSample sample;
    if (renderer) {
        if (!scene->animations.empty()) {
            ENCORE_TRY(renderer->setAnimationTime(animationTime));
        }
        lastFrame = renderer->renderFrame(camera(), float(animationTime));
        sample.cpuMilliseconds = lastFrame.cpuMilliseconds();
        sample.gpuMilliseconds = lastFrame.gpuMilliseconds;
    } else {
        const render::FrameTiming timing =
            animometer->renderFrame(float(animationTime), timer ? &*timer : nullptr);
        lastFrame = {};
        static_cast<render::FrameTiming&>(lastFrame) = timing;
        lastFrame.counters = animometer->lastFrameCounters();
        lastFrame.bundleContents = animometer->bundleContents();
        sample.cpuMilliseconds = timing.cpuMilliseconds();
        sample.gpuMilliseconds = timing.gpuMilliseconds;
    }
    history.push_back(sample);
    if (history.size() > kHistoryFrames) {
        history.pop_front();
    }

    ENCORE_TRY_ASSIGN(auto texture, surface->acquire());
    const wgpu::TextureView view = texture.CreateView();
    const render::RenderTarget& target = renderer ? renderer->target() : animometer->target();
    const wgpu::Device& device = context->device();

    // The scene alone first: screenshots without the overlay are read back from here.
    wgpu::CommandEncoder commands = device.CreateCommandEncoder();
    // sRGB surface: decoded here, encoded again there (exact); linear surface: the bytes.
    presenter->encode(commands, surface->srgb() ? target.outputView() : target.outputBytesView(),
                      view);
    wgpu::CommandBuffer sceneCommands = commands.Finish();
    context->queue().Submit(1, &sceneCommands);
    auto saveScreenshots = [&](bool withOverlay) -> Result<void> {
        for (const PendingScreenshot& screenshot : screenshots) {
            if (screenshot.overlay != withOverlay) {
                continue;
            }
            // What the window shows; a surface that cannot be copied gives the scene's image.
            ENCORE_TRY_ASSIGN(auto image, surface->copyable()
                                              ? gpu::readTexture(*context, texture)
                                              : gpu::readTexture(*context, target.colorTexture()));
            ENCORE_TRY(image::writePng(screenshot.path, image));
            if (options.report) {
                options.report("screenshot " + screenshot.path);
            }
        }
        return {};
    };
    ENCORE_TRY(saveScreenshots(false));
    if (overlayVisible) {
        buildOverlay();
        wgpu::CommandEncoder overlayCommands = device.CreateCommandEncoder();
        overlay->encode(overlayCommands, view, width, height);
        wgpu::CommandBuffer finished = overlayCommands.Finish();
        context->queue().Submit(1, &finished);
    }
    ENCORE_TRY(saveScreenshots(true));
    screenshots.clear();
    surface->present();
    ++frameNumber;

    const auto now = std::chrono::steady_clock::now();
    if (lastPresent.time_since_epoch().count() != 0) {
        frameIntervals.push_back(std::chrono::duration<double>(now - lastPresent).count());
        if (frameIntervals.size() > 60) {
            frameIntervals.pop_front();
        }
    }
    lastPresent = now;
    return context->checkNoErrors("Rendering the viewer's frame " + std::to_string(frameNumber));
}

Result<void> Viewer::run() {
    State& s = *mState;
    s.window->setTitle("encore view - " + s.strategyLabel());
    if (s.options.script) {
        for (const ScriptStep& step : *s.options.script) {
            if (s.quit || s.window->closeRequested()) {
                break;
            }
            ENCORE_TRY(s.runScriptStep(step));
        }
        return {};
    }
    auto last = std::chrono::steady_clock::now();
    while (!s.quit && !s.window->closeRequested()) {
        for (const InputEvent& event : s.window->pollEvents()) {
            ENCORE_TRY(s.handle(event));
        }
        const auto now = std::chrono::steady_clock::now();
        const double delta = std::chrono::duration<double>(now - last).count();
        last = now;
        ENCORE_TRY(s.renderFrame(delta));
        s.window->setTitle("encore view - " + s.strategyLabel());
    }
    return {};
}

}  // namespace encore::view
