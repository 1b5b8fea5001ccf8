#include "view/Viewer.h"

#include <cmath>

#include "encore/scene/AnimationPlayer.h"
#include "encore/scene/SceneData.h"
#include "render/renderer/RendererCore.h"
#include "view/ViewerState.h"

namespace encore::view {

Viewer::Viewer(std::unique_ptr<State> state) : mState(std::move(state)) {}

Viewer::~Viewer() {
    if (mState) {
        // The surface goes before the renderer and the context's device it was configured with.
        mState->surface.reset();
    }
}

Result<std::unique_ptr<Viewer>> Viewer::create(gpu::Context& context,
                                               Window& window,
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

    ENCORE_TRY_ASSIGN(s.surface, WindowSurface::create(context, window, s.options.present));
    s.width = s.surface->width();
    s.height = s.surface->height();
    ENCORE_TRY_ASSIGN(s.presenter,
                      Presenter::create(context.device(), *s.shaders, s.surface->format()));
    ENCORE_TRY_ASSIGN(s.overlay, Overlay::create(context.device(), context.queue(), *s.shaders,
                                                 s.surface->format()));
    s.timer = gpu::GpuTimer::create(context);

    if (s.options.animometer) {
        ENCORE_TRY(s.createAnimometer(s.options.animometer->bundle));
    } else {
        render::RendererOptions rendererOptions = s.options.renderer;
        rendererOptions.target.width = s.width;
        rendererOptions.target.height = s.height;
        ENCORE_TRY_ASSIGN(s.renderer, render::Renderer::create(context, rendererOptions));
        internals(*s.renderer).setGpuTimer(s.timer ? &*s.timer : nullptr);
        // The window's clock runs on: animations play round and round, not once.
        s.renderer->setPlaybackMode(scene::PlaybackMode::Loop);
        if (!s.options.variant.empty()) {
            ENCORE_TRY_ASSIGN(const scene::VariantId variant,
                              scene::resolveVariant(*s.scene, s.options.variant));
            s.variantIndex = int(variant.index());
        }
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
    animometer.reset();
    ENCORE_TRY_ASSIGN(animometer,
                      render::AnimometerScene::create(*context, *shaders, animometerOptions));
    options.animometer->bundle = bundleDraws;
    return {};
}

Result<void> Viewer::State::prepareScene() {
    ENCORE_TRY(renderer->prepare(*scene, kind, bundle));
    // A new strategy starts from all animations; keep the one selected.
    if (animationIndex >= 0) {
        ENCORE_TRY(renderer->selectAnimation(std::to_string(animationIndex)));
    }
    if (variantIndex >= 0) {
        ENCORE_TRY(renderer->selectVariant(scene::VariantId(std::size_t(variantIndex))));
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

Result<void> Viewer::State::cycleVariant(int step) {
    if (!renderer || scene->variants.empty()) {
        show("The scene has no material variants (KHR_materials_variants).");
        return {};
    }
    const int count = int(scene->variants.size());
    // -1 (the default materials), 0 .. count - 1, around.
    variantIndex = (variantIndex + 1 + step + (count + 1)) % (count + 1) - 1;
    // Only material bindings change: the GPU scene uploads nothing, bundles record again.
    ENCORE_TRY(renderer->selectVariant(
        variantIndex < 0 ? std::nullopt
                         : std::optional(scene::VariantId(std::size_t(variantIndex)))));
    if (variantIndex < 0) {
        show("material variant: default");
    } else {
        show("material variant " + std::to_string(variantIndex) + ": " +
             scene->variants[std::size_t(variantIndex)]);
    }
    return {};
}

void Viewer::State::drop(const std::string& path) {
    if (animometer) {
        show("The Animometer shows no files; run encore view on the file instead.", true);
        return;
    }
    auto loaded =
        options.loadScene ? options.loadScene(path) : scene::loadScene(path, scene::LoadOptions{});
    if (!loaded) {
        show(loaded.error().message, true);
        return;
    }
    auto previous = std::move(scene);
    scene = std::make_unique<scene::SceneData>(std::move(*loaded));
    const int previousAnimation = animationIndex;
    const int previousVariant = variantIndex;
    animationIndex = -1;
    variantIndex = -1;
    if (auto prepared = prepareScene(); !prepared) {
        show(prepared.error().message, true);
        scene = std::move(previous);
        animationIndex = previousAnimation;
        variantIndex = previousVariant;
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

}  // namespace encore::view
