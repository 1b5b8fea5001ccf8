#pragma once

// The state of the viewer (Viewer.h) that its files share, one idea each: Viewer.cpp (opening
// the viewer, and what changes the scene, strategy, camera and animation), ViewerControls.cpp
// (input), ViewerFrameLoop.cpp (the frame loop), ViewerHud.cpp (the overlay) and
// ViewerScriptDriver.cpp (scripted sessions).

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gpu/GpuTimer.h"
#include "shaders/ShaderLibrary.h"
#include "view/OrbitCamera.h"
#include "view/Overlay.h"
#include "view/Presenter.h"
#include "view/Viewer.h"

namespace encore::view {

// Frames in the overlay's graph of CPU and GPU times, the last ones kept.
inline constexpr std::size_t kHistoryFrames = 240;

// printf-style text for the overlay, screenshot names and the script's lines.
std::string format(const char* pattern, auto... values) {
    char text[512];
    std::snprintf(text, sizeof(text), pattern, values...);
    return text;
}

struct FrameSample {
    double cpuMilliseconds = 0.0;
    std::optional<double> gpuMilliseconds;
};

struct PendingScreenshot {
    std::string path;
    bool overlay = false;
};

struct Viewer::State {
    gpu::Context* context = nullptr;
    Window* window = nullptr;
    ViewerOptions options;
    std::unique_ptr<shaders::ShaderLibrary> shaders;
    std::optional<WindowSurface> surface;
    std::optional<Presenter> presenter;
    std::optional<Overlay> overlay;
    std::optional<gpu::GpuTimer> timer;

    // What is drawn: a model through the renderer, or the Animometer.
    std::unique_ptr<scene::SceneData> scene;
    std::optional<render::Renderer> renderer;
    std::optional<render::AnimometerScene> animometer;
    render::StrategyKind kind = render::StrategyKind::Bundles;
    bool bundle = false;

    std::uint32_t width = 0;
    std::uint32_t height = 0;
    // Until the user moves it, the camera is the one `encore render` uses (re-resolved on
    // resize); afterwards it orbits.
    std::optional<OrbitCamera> orbit;
    bool framing = false;  // F: the automatic framing instead of the initial camera.
    bool frozenCulling = false;

    double animationTime = 0.0;
    bool paused = false;
    int animationIndex = -1;  // -1: all animations.
    int variantIndex = -1;    // KHR_materials_variants; -1: the default materials.
    bool overlayVisible = true;
    std::string message;  // Shown in the overlay (errors in red).
    bool messageIsError = false;

    // Input state.
    bool orbiting = false;
    bool panning = false;
    double cursorX = 0.0;
    double cursorY = 0.0;

    // Measurements.
    render::FrameResult lastFrame;
    std::deque<FrameSample> history;
    std::deque<double> frameIntervals;  // Seconds between presented frames.
    std::chrono::steady_clock::time_point lastPresent{};
    std::uint64_t frameNumber = 0;
    std::vector<PendingScreenshot> screenshots;
    int screenshotCounter = 0;
    bool quit = false;

    // Viewer.cpp: the scene, the strategy, the camera and the animation.
    Result<void> prepareScene();
    Result<void> createAnimometer(bool bundle);
    render::Camera initialCamera(float aspect) const;
    render::Camera camera() const;
    OrbitCamera& startOrbit();
    std::string strategyLabel() const;
    Result<void> resize(std::uint32_t width, std::uint32_t height);
    Result<void> switchStrategy(render::StrategyKind kind, bool bundle);
    Result<void> toggleBundle();
    Result<void> cycleAnimation(int step);
    Result<void> cycleVariant(int step);
    void drop(const std::string& path);
    void show(std::string text, bool error = false);
    // ViewerControls.cpp: what each key, button, drag and wheel turn does.
    Result<void> handle(const InputEvent& event);
    Result<void> handleKey(int key, int modifiers);
    // ViewerFrameLoop.cpp: one frame drawn, presented and measured.
    Result<void> renderFrame(double deltaSeconds);
    // ViewerHud.cpp: the overlay drawn over the scene.
    void buildOverlay();
    void addFrustumLines(float yTop);
    // ViewerScriptDriver.cpp: a script's steps as input events and frames.
    Result<void> runScriptStep(const ScriptStep& step);
    std::string statsLine() const;
};

}  // namespace encore::view
