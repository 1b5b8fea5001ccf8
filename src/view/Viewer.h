#pragma once

// The interactive viewer (`encore view`): a window where a scene (or the Animometer) renders
// live through any strategy, with orbit controls, live strategy and bundling switches, a frozen
// culling frustum, animation and material variant controls, screenshots, dropped files and an
// overlay of frame times and call counts. See the README's "Interactive viewer" for the controls.
//
// The renderer draws into its own target as it does headless; each frame view::Presenter copies
// that image into the window's surface and view::Overlay draws over it in a pass of its own, so
// presenting never changes the scene's passes or bundles. A resize gives the renderer a new
// target size (Renderer::resize) and re-records nothing.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "encore/core/Result.h"
#include "encore/gpu/Context.h"
#include "encore/render/Renderer.h"
#include "encore/scene/SceneData.h"
#include "render/Animometer.h"
#include "view/ViewScript.h"
#include "view/Window.h"
#include "view/WindowSurface.h"

namespace encore::view {

struct ViewerOptions {
    // The renderer as `encore render` would create it; the target's size follows the window.
    render::RendererOptions renderer;
    render::StrategyKind strategy = render::StrategyKind::Bundles;
    bool bundle = false;  // Draw the strategy's frame from render bundles (the B key).
    // Set: the Animometer scene instead of a model (its own bundle switch).
    std::optional<render::AnimometerOptions> animometer;
    PresentPreference present = PresentPreference::Vsync;
    bool overlay = true;
    std::string animation;  // The animation to play (index or name); all when empty.
    // The KHR_materials_variants variant to show first (index or name); the default materials
    // when empty. V and shift + V cycle through the variants.
    std::string variant;
    // The camera for a scene and aspect before the user moves it: as `encore render` resolves
    // it, so that the window shows what `encore render` writes at the same size.
    std::function<Result<render::Camera>(const scene::SceneData&, float aspect)> initialCamera;
    // Loads a dropped file (the app prints its warnings).
    std::function<Result<scene::SceneData>(const std::string& path)> loadScene;
    // Lines for the user: saved screenshots, a script's `stats`.
    std::function<void(const std::string& line)> report;
    // A scripted session: runs these steps, with a fixed animation step, then ends.
    std::optional<std::vector<ScriptStep>> script;
};

class Viewer {
  public:
    // `scene` is null with options.animometer. The context and window must outlive the viewer.
    static Result<std::unique_ptr<Viewer>> create(gpu::Context& context,
                                                  Window& window,
                                                  std::unique_ptr<scene::SceneData> scene,
                                                  ViewerOptions options);
    ~Viewer();

    // Runs until the window is closed, escape or Q is pressed, or the script ends. Fails on a
    // WebGPU error or device loss, or a failing script step (an unwritable screenshot, a resize
    // the window system does not apply).
    Result<void> run();

  private:
    struct State;
    explicit Viewer(std::unique_ptr<State> state);
    std::unique_ptr<State> mState;
};

}  // namespace encore::view
