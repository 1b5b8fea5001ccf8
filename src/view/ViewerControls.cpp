// The key-to-action table and the mouse: what each input event does to the viewer's state.

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>

#include "view/ViewerState.h"

namespace encore::view {

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
        case GLFW_KEY_V:
            return cycleVariant(shift ? -1 : 1);
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

}  // namespace encore::view
