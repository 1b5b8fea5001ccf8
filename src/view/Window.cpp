#include "view/Window.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdlib>

// GLFW's native accessors. glfw3native.h would declare them, but with GLFW_EXPOSE_NATIVE_X11 it
// includes the Xrandr headers (another package) for monitor functions Encore does not use.
extern "C" {
struct _XDisplay* glfwGetX11Display(void);
unsigned long glfwGetX11Window(GLFWwindow* window);
}

namespace encore::view {

namespace {
std::string gLastGlfwError;
}

struct Window::State {
    GLFWwindow* window = nullptr;
    std::vector<InputEvent> events;

    ~State() {
        if (window) {
            glfwDestroyWindow(window);
        }
        glfwTerminate();
    }

    static State& of(GLFWwindow* window) {
        return *static_cast<State*>(glfwGetWindowUserPointer(window));
    }
};

Window::Window(std::unique_ptr<State> state) : mState(std::move(state)) {}
Window::Window(Window&&) noexcept = default;
Window& Window::operator=(Window&&) noexcept = default;
Window::~Window() = default;

Result<Window> Window::create(const std::string& title, std::uint32_t width, std::uint32_t height) {
    glfwSetErrorCallback([](int, const char* description) { gLastGlfwError = description; });
    const char* display = std::getenv("DISPLAY");
    if (!display || !*display) {
        return makeError(ErrorCode::NoDisplay,
                         "No display to open a window on (DISPLAY is not set); `encore render` "
                         "renders the same picture headless into a PNG.");
    }
    if (!glfwInit()) {
        return makeError(ErrorCode::NoDisplay,
                         "Cannot open a window on display '" + std::string(display) + "' (" +
                             gLastGlfwError +
                             "); `encore render` renders the same picture headless into a PNG.");
    }
    auto state = std::make_unique<State>();  // From here on terminates GLFW when it goes.
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    state->window = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
    if (!state->window) {
        return makeError(ErrorCode::NoDisplay, "Cannot create a window (" + gLastGlfwError +
                                                   "); `encore render` renders headless.");
    }
    GLFWwindow* window = state->window;
    glfwSetWindowUserPointer(window, state.get());
    glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int modifiers) {
        if (action == GLFW_REPEAT) {
            action = GLFW_PRESS;  // Held keys keep orbiting.
        }
        InputEvent event;
        event.kind = InputKind::Key;
        event.key = key;
        event.pressed = action == GLFW_PRESS;
        event.modifiers = modifiers;
        State::of(w).events.push_back(std::move(event));
    });
    glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int modifiers) {
        InputEvent event;
        event.kind = InputKind::MouseButton;
        event.key = button;
        event.pressed = action == GLFW_PRESS;
        event.modifiers = modifiers;
        State::of(w).events.push_back(std::move(event));
    });
    glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
        InputEvent event;
        event.kind = InputKind::CursorMove;
        event.x = x;
        event.y = y;
        State::of(w).events.push_back(std::move(event));
    });
    glfwSetScrollCallback(window, [](GLFWwindow* w, double x, double y) {
        InputEvent event;
        event.kind = InputKind::Scroll;
        event.x = x;
        event.y = y;
        State::of(w).events.push_back(std::move(event));
    });
    glfwSetFramebufferSizeCallback(window, [](GLFWwindow* w, int width, int height) {
        InputEvent event;
        event.kind = InputKind::Resize;
        event.width = std::uint32_t(width);
        event.height = std::uint32_t(height);
        State::of(w).events.push_back(std::move(event));
    });
    glfwSetDropCallback(window, [](GLFWwindow* w, int count, const char** paths) {
        InputEvent event;
        event.kind = InputKind::Drop;
        event.paths.assign(paths, paths + count);
        State::of(w).events.push_back(std::move(event));
    });
    return Window(std::move(state));
}

std::vector<InputEvent> Window::pollEvents() {
    glfwPollEvents();
    return std::exchange(mState->events, {});
}

bool Window::closeRequested() const {
    return glfwWindowShouldClose(mState->window);
}

void Window::requestClose() {
    glfwSetWindowShouldClose(mState->window, GLFW_TRUE);
}

std::pair<std::uint32_t, std::uint32_t> Window::framebufferSize() const {
    int width = 0;
    int height = 0;
    glfwGetFramebufferSize(mState->window, &width, &height);
    return {std::uint32_t(width), std::uint32_t(height)};
}

void Window::setSize(std::uint32_t width, std::uint32_t height) {
    glfwSetWindowSize(mState->window, int(width), int(height));
}

void Window::setTitle(const std::string& title) {
    glfwSetWindowTitle(mState->window, title.c_str());
}

void* Window::x11Display() const {
    return glfwGetX11Display();
}

std::uint64_t Window::x11Window() const {
    return glfwGetX11Window(mState->window);
}

}  // namespace encore::view
