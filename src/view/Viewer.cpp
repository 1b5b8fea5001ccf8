#include "encore/view/Viewer.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <thread>

#include "encore/gpu/GpuTimer.h"
#include "encore/gpu/Readback.h"
#include "encore/image/ImageCodec.h"
#include "encore/scene/AnimationPlayer.h"
#include "encore/shaders/ShaderLibrary.h"
#include "encore/view/OrbitCamera.h"
#include "encore/view/Overlay.h"
#include "encore/view/Presenter.h"

namespace encore::view {

namespace {

constexpr double kScriptFrameSeconds = 1.0 / 60.0;
constexpr std::size_t kHistoryFrames = 240;
constexpr OverlayColor kText{235, 235, 235, 255};
constexpr OverlayColor kDim{170, 170, 170, 255};
constexpr OverlayColor kError{255, 96, 96, 255};
constexpr OverlayColor kCpuColor{110, 220, 110, 255};
constexpr OverlayColor kGpuColor{255, 170, 60, 255};
constexpr OverlayColor kFrustumColor{255, 230, 60, 255};
constexpr OverlayColor kPanel{0, 0, 0, 150};

std::string format(const char* pattern, auto... values) {
    char text[512];
    std::snprintf(text, sizeof(text), pattern, values...);
    return text;
}

std::string fileName(const std::filesystem::path& path) {
    return path.filename().string();
}

struct FrameSample {
    double cpuMilliseconds = 0.0;
    std::optional<double> gpuMilliseconds;
};

struct PendingScreenshot {
    std::string path;
    bool overlay = false;
};

}  // namespace

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

    Result<void> prepareScene();
    Result<void> createAnimometer(bool bundle);
    render::Camera initialCamera(float aspect) const;
    render::Camera camera() const;
    OrbitCamera& startOrbit();
    std::string strategyLabel() const;
    Result<void> resize(std::uint32_t width, std::uint32_t height);
    Result<void> handle(const InputEvent& event);
    Result<void> handleKey(int key, int modifiers);
    Result<void> switchStrategy(render::StrategyKind kind, bool bundle);
    Result<void> toggleBundle();
    Result<void> cycleAnimation(int step);
    void drop(const std::string& path);
    void show(std::string text, bool error = false);
    Result<void> renderFrame(double deltaSeconds);
    void buildOverlay();
    void addFrustumLines(float yTop);
    Result<void> runScriptStep(const ScriptStep& step);
    std::string statsLine() const;
};

Viewer::Viewer(std::unique_ptr<State> state) : mState(std::move(state)) {}

Viewer::~Viewer() {
    if (mState) {
        // The surface goes before the renderer and the context's device it was configured with.
        mState->surface.reset();
    }
}

Result<std::unique_ptr<Viewer>> Viewer::create(gpu::Context& context, Window& window,
                                               std::unique_ptr<scene::SceneData> scene,
                                               ViewerOptions options) {
    auto state = std::make_unique<State>();
    State& s = *state;
    s.context = &context;
    s.window = &window;
    s.options = std::move(options);
    s.kind = s.options.strategy;
    s.bundle = s.options.bundle;
    s.overlayVisible = s.options.overlay;
    s.scene = std::move(scene);
    s.shaders = std::make_unique<shaders::ShaderLibrary>(context.device());

    auto surface = WindowSurface::create(context, window, s.options.present);
    if (!surface) {
        return surface.error();
    }
    s.surface = std::move(*surface);
    s.width = s.surface->width();
    s.height = s.surface->height();
    auto presenter = Presenter::create(context.device(), *s.shaders, s.surface->format());
    if (!presenter) {
        return presenter.error();
    }
    s.presenter = std::move(*presenter);
    auto overlay = Overlay::create(context.device(), context.queue(), *s.shaders,
                                   s.surface->format());
    if (!overlay) {
        return overlay.error();
    }
    s.overlay = std::move(*overlay);
    s.timer = gpu::GpuTimer::create(context);

    if (s.options.animometer) {
        ENCORE_TRY(s.createAnimometer(s.options.animometer->bundle));
    } else {
        render::RendererOptions rendererOptions = s.options.renderer;
        rendererOptions.target.width = s.width;
        rendererOptions.target.height = s.height;
        rendererOptions.target.presentable = true;
        auto renderer = render::Renderer::create(context, rendererOptions);
        if (!renderer) {
            return renderer.error();
        }
        s.renderer = std::move(*renderer);
        s.renderer->setGpuTimer(s.timer ? &*s.timer : nullptr);
        // The window's clock runs on: animations play round and round, not once.
        s.renderer->setPlaybackMode(scene::PlaybackMode::Loop);
        ENCORE_TRY(s.prepareScene());
        if (!s.options.animation.empty()) {
            if (auto found = scene::findAnimation(*s.scene, s.options.animation)) {
                s.animationIndex = int(found->index());
            }
            ENCORE_TRY(s.renderer->selectAnimation(s.options.animation));
        }
    }
    ENCORE_TRY(context.checkNoErrors("Opening the viewer"));
    return std::unique_ptr<Viewer>(new Viewer(std::move(state)));
}

Result<void> Viewer::State::createAnimometer(bool bundleDraws) {
    render::AnimometerOptions animometerOptions = *options.animometer;
    animometerOptions.bundle = bundleDraws;
    animometerOptions.width = width;
    animometerOptions.height = height;
    animometerOptions.presentable = true;
    animometer.reset();
    auto created = render::AnimometerScene::create(*context, *shaders, animometerOptions);
    if (!created) {
        return created.error();
    }
    animometer = std::move(*created);
    options.animometer->bundle = bundleDraws;
    return {};
}

Result<void> Viewer::State::prepareScene() {
    ENCORE_TRY(renderer->prepare(*scene, kind, bundle));
    // A new strategy starts from all animations; keep the one selected.
    if (animationIndex >= 0) {
        ENCORE_TRY(renderer->selectAnimation(std::to_string(animationIndex)));
    }
    if (frozenCulling) {
        renderer->setCullingCamera(camera());
    }
    return {};
}

render::Camera Viewer::State::initialCamera(float aspect) const {
    if (framing || !options.initialCamera) {
        return render::Camera::framing(scene->bounds, aspect);
    }
    auto resolved = options.initialCamera(*scene, aspect);
    return resolved ? *resolved : render::Camera::framing(scene->bounds, aspect);
}

render::Camera Viewer::State::camera() const {
    const float aspect = float(width) / float(height);
    if (orbit) {
        return orbit->camera(aspect);
    }
    if (!scene) {
        return {};
    }
    return initialCamera(aspect);
}

OrbitCamera& Viewer::State::startOrbit() {
    if (!orbit && scene) {
        const render::Camera current = camera();
        const glm::vec3 center = 0.5f * (scene->bounds.min + scene->bounds.max);
        float distance = glm::length(center - current.position);
        if (!(distance > 0.0f) || !std::isfinite(distance)) {
            distance = 1.0f;
        }
        orbit = OrbitCamera::from(current, distance);
    }
    if (!orbit) {
        orbit = OrbitCamera{};
    }
    return *orbit;
}

std::string Viewer::State::strategyLabel() const {
    if (animometer) {
        return std::string("animometer, ") + (options.animometer->bundle ? "bundle" : "direct");
    }
    return render::strategyChoiceName({kind, bundle});
}

void Viewer::State::show(std::string text, bool error) {
    message = std::move(text);
    messageIsError = error;
}

Result<void> Viewer::State::resize(std::uint32_t newWidth, std::uint32_t newHeight) {
    if (newWidth == 0 || newHeight == 0) {
        return {};  // Minimised: keep the old size until it comes back.
    }
    if (newWidth == width && newHeight == height) {
        return {};
    }
    width = newWidth;
    height = newHeight;
    surface->configure(width, height);
    if (renderer) {
        ENCORE_TRY(renderer->resize(width, height));
    }
    if (animometer) {
        ENCORE_TRY(animometer->resize(width, height));
    }
    return {};
}

Result<void> Viewer::State::switchStrategy(render::StrategyKind newKind, bool newBundle) {
    if (animometer) {
        show("The Animometer has no strategies: B switches between direct and bundled draws.");
        return {};
    }
    const render::StrategyKind oldKind = kind;
    const bool oldBundle = bundle;
    kind = newKind;
    bundle = newBundle;
    // Only the strategy is made again: the GPU scene, its edits, the animation selection and a
    // frozen culling camera stay.
    if (auto switched = renderer->setStrategy(kind, bundle); !switched) {
        show(switched.error().message, true);
        kind = oldKind;
        bundle = oldBundle;
        ENCORE_TRY(renderer->setStrategy(kind, bundle));
        return {};
    }
    show("strategy " + strategyLabel());
    return {};
}

Result<void> Viewer::State::toggleBundle() {
    if (animometer) {
        ENCORE_TRY(createAnimometer(!options.animometer->bundle));
        show(std::string("animometer: ") + (options.animometer->bundle ? "bundle" : "direct"));
        return {};
    }
    if (auto direct = render::directKind(kind)) {
        return switchStrategy(*direct, false);
    }
    if (bundle) {
        return switchStrategy(kind, false);
    }
    if (auto bundled = render::bundledKind(kind)) {
        return switchStrategy(*bundled, false);
    }
    return switchStrategy(kind, true);
}

Result<void> Viewer::State::cycleAnimation(int step) {
    if (!renderer || scene->animations.empty()) {
        show("The scene has no animations.");
        return {};
    }
    const int count = int(scene->animations.size());
    // -1 (all), 0 .. count - 1, around.
    animationIndex = (animationIndex + 1 + step + (count + 1)) % (count + 1) - 1;
    ENCORE_TRY(renderer->selectAnimation(animationIndex < 0 ? std::string()
                                                            : std::to_string(animationIndex)));
    if (animationIndex < 0) {
        show("animation: all");
    } else {
        const std::string& name = scene->animations[std::size_t(animationIndex)].name;
        show("animation " + std::to_string(animationIndex) + (name.empty() ? "" : ": " + name));
    }
    return {};
}

void Viewer::State::drop(const std::string& path) {
    if (animometer) {
        show("The Animometer shows no files; run encore view on the file instead.", true);
        return;
    }
    auto loaded = options.loadScene ? options.loadScene(path)
                                    : scene::loadScene(path, scene::LoadOptions{});
    if (!loaded) {
        show(loaded.error().message, true);
        return;
    }
    auto previous = std::move(scene);
    scene = std::make_unique<scene::SceneData>(std::move(*loaded));
    const int previousAnimation = animationIndex;
    animationIndex = -1;
    if (auto prepared = prepareScene(); !prepared) {
        show(prepared.error().message, true);
        scene = std::move(previous);
        animationIndex = previousAnimation;
        if (auto restored = prepareScene(); !restored) {
            show(restored.error().message, true);
        }
        return;
    }
    orbit.reset();
    framing = true;  // A dropped file has no command-line camera.
    animationTime = 0.0;
    show("opened " + path);
}

Result<void> Viewer::State::handleKey(int key, int modifiers) {
    const bool shift = (modifiers & GLFW_MOD_SHIFT) != 0;
    constexpr float kStep = 0.08f;
    if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9) {
        const auto strategies = render::allStrategies();
        const std::size_t index = std::size_t(key - GLFW_KEY_1);
        if (index < strategies.size()) {
            return switchStrategy(strategies[index], false);
        }
        return {};
    }
    switch (key) {
        case GLFW_KEY_ESCAPE:
        case GLFW_KEY_Q:
            quit = true;
            break;
        case GLFW_KEY_F:
            orbit.reset();
            framing = true;
            show("framed the scene");
            break;
        case GLFW_KEY_B:
            return toggleBundle();
        case GLFW_KEY_C:
            if (renderer) {
                frozenCulling = !frozenCulling;
                renderer->setCullingCamera(frozenCulling ? std::optional(camera()) : std::nullopt);
                show(frozenCulling ? "" : "culling follows the camera again");
            }
            break;
        case GLFW_KEY_SPACE:
            paused = !paused;
            show(paused ? "animation paused" : "animation playing");
            break;
        case GLFW_KEY_LEFT_BRACKET:
            return cycleAnimation(-1);
        case GLFW_KEY_RIGHT_BRACKET:
            return cycleAnimation(1);
        case GLFW_KEY_S:
            screenshots.push_back({format("encore-view-%04d.png", ++screenshotCounter), shift});
            break;
        case GLFW_KEY_O:
            overlayVisible = !overlayVisible;
            break;
        case GLFW_KEY_LEFT:
        case GLFW_KEY_RIGHT:
        case GLFW_KEY_UP:
        case GLFW_KEY_DOWN: {
            const float x = key == GLFW_KEY_LEFT ? -1.0f : key == GLFW_KEY_RIGHT ? 1.0f : 0.0f;
            const float y = key == GLFW_KEY_UP ? 1.0f : key == GLFW_KEY_DOWN ? -1.0f : 0.0f;
            if (shift) {
                startOrbit().pan(x * kStep, y * kStep);
            } else {
                startOrbit().orbit(x * kStep * 2.0f, y * kStep * 2.0f);
            }
            break;
        }
        case GLFW_KEY_EQUAL:
        case GLFW_KEY_KP_ADD:
            startOrbit().zoom(0.9f);
            break;
        case GLFW_KEY_MINUS:
        case GLFW_KEY_KP_SUBTRACT:
            startOrbit().zoom(1.0f / 0.9f);
            break;
        default:
            break;
    }
    return {};
}

Result<void> Viewer::State::handle(const InputEvent& event) {
    switch (event.kind) {
        case InputKind::Key:
            if (event.pressed) {
                return handleKey(event.key, event.modifiers);
            }
            break;
        case InputKind::MouseButton: {
            const bool panButton = event.key == GLFW_MOUSE_BUTTON_RIGHT ||
                                   event.key == GLFW_MOUSE_BUTTON_MIDDLE ||
                                   (event.modifiers & GLFW_MOD_SHIFT) != 0;
            if (event.pressed) {
                orbiting = !panButton;
                panning = panButton;
            } else {
                orbiting = panning = false;
            }
            break;
        }
        case InputKind::CursorMove: {
            const double dx = event.x - cursorX;
            const double dy = event.y - cursorY;
            cursorX = event.x;
            cursorY = event.y;
            if (orbiting && scene) {
                startOrbit().orbit(float(-dx) * 0.008f, float(dy) * 0.008f);
            } else if (panning && scene) {
                const float perPixel = 1.0f / float(std::max<std::uint32_t>(height, 1));
                startOrbit().pan(float(-dx) * perPixel, float(dy) * perPixel);
            }
            break;
        }
        case InputKind::Scroll:
            if (scene) {
                startOrbit().zoom(std::pow(0.9f, float(event.y)));
            }
            break;
        case InputKind::Resize:
            return resize(event.width, event.height);
        case InputKind::Drop:
            if (!event.paths.empty()) {
                drop(event.paths.front());
            }
            break;
    }
    return {};
}

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

    auto texture = surface->acquire();
    if (!texture) {
        return texture.error();
    }
    const wgpu::TextureView view = texture->CreateView();
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
            auto image = surface->copyable() ? gpu::readTexture(*context, *texture)
                                             : gpu::readTexture(*context, target.colorTexture());
            if (!image) {
                return image.error();
            }
            ENCORE_TRY(image::writePng(screenshot.path, *image));
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

void Viewer::State::addFrustumLines(float) {
    if (!renderer || !renderer->cullingCamera()) {
        return;
    }
    const render::Camera& frozen = *renderer->cullingCamera();
    const glm::mat4 inverse = glm::inverse(frozen.viewProjection());
    // Far corners at a finite depth: the frozen camera's distance to the scene's far side.
    const glm::vec3 center = 0.5f * (scene->bounds.min + scene->bounds.max);
    const float reach =
        glm::length(center - frozen.position) + glm::length(scene->bounds.max - center);
    glm::vec3 corners[8];
    const glm::vec2 ndc[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (int i = 0; i < 4; ++i) {
        auto unproject = [&](float depth) {
            const glm::vec4 point = inverse * glm::vec4(ndc[i], depth, 1.0f);
            return glm::vec3(point) / point.w;
        };
        const glm::vec3 nearPoint = unproject(0.0f);
        const glm::vec3 direction = glm::normalize(unproject(0.5f) - nearPoint);
        corners[i] = nearPoint;
        corners[i + 4] = frozen.position + direction * reach;
    }
    const glm::mat4 viewProjection = camera().viewProjection();
    auto toScreen = [&](const glm::vec3& point) -> std::optional<glm::vec2> {
        const glm::vec4 clip = viewProjection * glm::vec4(point, 1.0f);
        if (clip.w <= 1e-6f) {
            return std::nullopt;
        }
        const glm::vec2 ndcPoint = glm::vec2(clip) / clip.w;
        return glm::vec2((ndcPoint.x * 0.5f + 0.5f) * float(width),
                         (0.5f - ndcPoint.y * 0.5f) * float(height));
    };
    const int edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                              {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    for (const auto& edge : edges) {
        const auto from = toScreen(corners[edge[0]]);
        const auto to = toScreen(corners[edge[1]]);
        if (from && to) {
            overlay->addLine(*from, *to, 2.0f, kFrustumColor);
        }
    }
}

void Viewer::State::buildOverlay() {
    overlay->clear();
    addFrustumLines(0.0f);
    std::vector<std::pair<std::string, OverlayColor>> lines;
    double fps = 0.0;
    if (!frameIntervals.empty()) {
        double sum = 0.0;
        for (double interval : frameIntervals) {
            sum += interval;
        }
        fps = sum > 0.0 ? double(frameIntervals.size()) / sum : 0.0;
    }
    lines.push_back({format("%.1f fps (%.2f ms)  %ux%u  present %s", fps,
                            fps > 0.0 ? 1000.0 / fps : 0.0, width, height,
                            presentModeName(surface->presentMode())),
                     kText});
    lines.push_back({"strategy " + strategyLabel(), kText});
    std::string gpu = lastFrame.gpuMilliseconds
                          ? format("%.3f ms", *lastFrame.gpuMilliseconds)
                          : std::string("n/a (no timestamp queries)");
    lines.push_back({format("CPU encode %.3f ms  submit %.3f ms", lastFrame.encodeMilliseconds,
                            lastFrame.submitMilliseconds),
                     kCpuColor});
    lines.push_back({"GPU " + gpu, kGpuColor});
    const std::uint64_t bundlesRecorded =
        renderer && renderer->strategy() ? renderer->strategy()->bundlesRecorded()
        : animometer && options.animometer->bundle ? 1
                                                   : 0;
    lines.push_back({format("draws %llu  executeBundles %llu  draws in bundles %llu",
                            (unsigned long long)lastFrame.counters.drawCalls(),
                            (unsigned long long)lastFrame.counters.executeBundles,
                            (unsigned long long)lastFrame.bundleContents.drawCalls()),
                     kText});
    lines.push_back({format("bundles recorded %llu", (unsigned long long)bundlesRecorded), kText});
    if (scene) {
        std::string animation;
        if (!scene->animations.empty()) {
            animation = animationIndex < 0 ? "  animation: all"
                                           : "  animation " + std::to_string(animationIndex);
            animation += paused ? " (paused)" : "";
        }
        lines.push_back({fileName(scene->sourcePath) + animation, kDim});
    }
    if (frozenCulling) {
        lines.push_back({"culling frustum frozen (C)", kFrustumColor});
    }
    lines.push_back({context->adapterDescription().summary(), kDim});
    if (!message.empty()) {
        lines.push_back({message, messageIsError ? kError : kDim});
    }

    constexpr float kScale = 2.0f;
    constexpr float kMargin = 8.0f;
    constexpr float kLineHeight = 9.0f * kScale;
    float panelWidth = 0.0f;
    for (const auto& [text, color] : lines) {
        panelWidth = std::max(panelWidth, Overlay::measureText(text, kScale).x);
    }
    const float graphHeight = 48.0f;
    panelWidth = std::min(std::max(panelWidth, 2.0f * kHistoryFrames) + 2.0f * kMargin,
                          float(width));
    const float panelHeight = float(lines.size()) * kLineHeight + graphHeight + 3.0f * kMargin;
    overlay->addRectangle(0.0f, 0.0f, panelWidth, panelHeight, kPanel);
    float y = kMargin;
    for (const auto& [text, color] : lines) {
        overlay->addText(kMargin, y, text, color, kScale);
        y += kLineHeight;
    }
    // The last seconds of CPU and GPU time, each frame a bar, on one scale.
    y += kMargin;
    double highest = 1.0;
    for (const FrameSample& frame : history) {
        highest = std::max({highest, frame.cpuMilliseconds, frame.gpuMilliseconds.value_or(0.0)});
    }
    float x = kMargin;
    for (const FrameSample& frame : history) {
        const float cpu = float(frame.cpuMilliseconds / highest) * graphHeight;
        overlay->addRectangle(x, y + graphHeight - cpu, 1.0f, cpu, kCpuColor);
        if (frame.gpuMilliseconds) {
            const float gpuHeight = float(*frame.gpuMilliseconds / highest) * graphHeight;
            overlay->addRectangle(x + 1.0f, y + graphHeight - gpuHeight, 1.0f, gpuHeight,
                                  kGpuColor);
        }
        x += 2.0f;
    }
    overlay->addText(kMargin + 2.0f * kHistoryFrames + 4.0f, y,
                     format("%.1f ms", highest), kDim, 1.5f);

    const std::string help =
        "drag orbit  right-drag pan  wheel zoom  F frame  1-8 strategy  B bundle  C freeze "
        "culling  space pause  [ ] animation  S screenshot  O overlay";
    const float helpHeight = 9.0f * 1.5f;
    overlay->addRectangle(0.0f, float(height) - helpHeight - 6.0f, float(width), helpHeight + 6.0f,
                          kPanel);
    overlay->addText(kMargin, float(height) - helpHeight - 2.0f, help, kDim, 1.5f);
}

std::string Viewer::State::statsLine() const {
    std::string label = strategyLabel();
    std::replace(label.begin(), label.end(), ' ', '_');
    std::string line = "stats strategy=" + label;
    const std::uint64_t bundlesRecorded =
        renderer && renderer->strategy() ? renderer->strategy()->bundlesRecorded()
        : animometer && options.animometer->bundle ? 1
                                                   : 0;
    line += format(" bundled=%d size=%ux%u frames=%llu bundlesRecorded=%llu draws=%llu "
                   "executeBundles=%llu",
                   renderer ? int(renderer->bundled()) : int(options.animometer->bundle), width,
                   height, (unsigned long long)frameNumber, (unsigned long long)bundlesRecorded,
                   (unsigned long long)lastFrame.counters.drawCalls(),
                   (unsigned long long)lastFrame.counters.executeBundles);
    if (renderer) {
        // GPU scenes built and bytes uploaded since the viewer opened: a switch of strategy
        // changes neither.
        line += format(" sceneUploads=%llu uploadedBytes=%llu",
                       (unsigned long long)renderer->sceneUploads(),
                       (unsigned long long)renderer->uploadedBytes());
    }
    if (scene) {
        line += " scene=" + scene->sourcePath.string();
    }
    line += std::string(" cullingFrozen=") + (frozenCulling ? "1" : "0");
    if (!message.empty() && messageIsError) {
        line += " error=" + message;
    }
    return line;
}

Result<void> Viewer::State::runScriptStep(const ScriptStep& step) {
    auto pressRelease = [&](int key) -> Result<void> {
        InputEvent press;
        press.kind = InputKind::Key;
        press.key = key;
        press.pressed = true;
        ENCORE_TRY(handle(press));
        press.pressed = false;
        return handle(press);
    };
    switch (step.command) {
        case ScriptCommand::Frames:
            for (std::uint32_t i = 0; i < step.count && !quit; ++i) {
                for (const InputEvent& event : window->pollEvents()) {
                    ENCORE_TRY(handle(event));
                }
                ENCORE_TRY(renderFrame(kScriptFrameSeconds));
            }
            return {};
        case ScriptCommand::Key:
            return pressRelease(step.key);
        case ScriptCommand::Drag: {
            InputEvent event;
            event.kind = InputKind::CursorMove;
            event.x = cursorX;
            event.y = cursorY;
            ENCORE_TRY(handle(event));
            InputEvent button;
            button.kind = InputKind::MouseButton;
            button.key = step.key;
            button.pressed = true;
            ENCORE_TRY(handle(button));
            event.x += step.x;
            event.y += step.y;
            ENCORE_TRY(handle(event));
            button.pressed = false;
            return handle(button);
        }
        case ScriptCommand::Scroll: {
            InputEvent event;
            event.kind = InputKind::Scroll;
            event.y = step.y;
            return handle(event);
        }
        case ScriptCommand::Resize: {
            window->setSize(step.width, step.height);
            // The window system applies the size asynchronously; wait for its event.
            const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
            while (std::chrono::steady_clock::now() < deadline) {
                for (const InputEvent& event : window->pollEvents()) {
                    ENCORE_TRY(handle(event));
                }
                if (width == step.width && height == step.height) {
                    return {};
                }
                std::this_thread::sleep_for(std::chrono::milliseconds(5));
            }
            return makeError(ErrorCode::DeviceError,
                             format("script line %d: the window system did not resize the window "
                                    "to %ux%u (it is %ux%u).",
                                    step.line, step.width, step.height, width, height));
        }
        case ScriptCommand::Drop: {
            InputEvent event;
            event.kind = InputKind::Drop;
            event.paths = {step.path};
            return handle(event);
        }
        case ScriptCommand::Screenshot:
            screenshots.push_back({step.path, step.overlay});
            // Saved with the next frame, as the window shows it.
            return renderFrame(kScriptFrameSeconds);
        case ScriptCommand::Stats:
            if (options.report) {
                options.report(statsLine());
            }
            return {};
        case ScriptCommand::Quit:
            quit = true;
            return {};
    }
    return {};
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
