#pragma once

// A desktop window for WebGPU (GLFW without a client API: WebGPU draws into it through a
// view::WindowSurface) and the input it received, as a queue of events. The viewer handles the
// events one by one; a scripted session pushes the same events, so scripts test what users do.
//
// One window per process (GLFW is initialised with the first and terminated with it). X11 only:
// Debian's GLFW 3.3 is built for X11, and Dawn's own GLFW helper needs GLFW 3.4.

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "encore/core/Result.h"

namespace encore::view {

enum class InputKind {
    Key,          // key: a GLFW key code; pressed or released; modifiers (GLFW_MOD_*).
    MouseButton,  // key: the button (GLFW_MOUSE_BUTTON_*); pressed or released; modifiers.
    CursorMove,   // x, y: the cursor in window coordinates.
    Scroll,       // x, y: the scroll offsets.
    Resize,       // width, height: the new framebuffer size in pixels.
    Drop,         // paths: the files dropped on the window.
};

struct InputEvent {
    InputKind kind = InputKind::Key;
    int key = 0;
    bool pressed = false;
    int modifiers = 0;
    double x = 0.0;
    double y = 0.0;
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::vector<std::string> paths;
};

class Window {
  public:
    // Fails with ErrorCode::NoDisplay when there is no display to open (no DISPLAY, or the X
    // server refuses), naming GLFW's reason.
    static Result<Window> create(const std::string& title,
                                 std::uint32_t width,
                                 std::uint32_t height);

    Window(Window&&) noexcept;
    Window& operator=(Window&&) noexcept;
    ~Window();

    // Processes pending window-system events without waiting and returns the input received.
    std::vector<InputEvent> pollEvents();
    bool closeRequested() const;
    void requestClose();
    // The drawable size in pixels.
    std::pair<std::uint32_t, std::uint32_t> framebufferSize() const;
    // Asks the window system for a new size; a Resize event follows once it is applied.
    void setSize(std::uint32_t width, std::uint32_t height);
    void setTitle(const std::string& title);

    // The native window, for creating a surface: an X11 Display* and Window.
    void* x11Display() const;
    std::uint64_t x11Window() const;

  private:
    struct State;
    explicit Window(std::unique_ptr<State> state);
    std::unique_ptr<State> mState;
};

}  // namespace encore::view
