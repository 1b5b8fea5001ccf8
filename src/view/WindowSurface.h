#pragma once

// The WebGPU surface of a view::Window (wgpu::SurfaceSourceXlibWindow), configured with the
// surface's preferred format. Presentation waits for the display (FIFO) unless asked for the
// lowest-latency mode the surface supports (Immediate, else Mailbox, else FIFO relaxed).
//
// The surface is configured with its preferred 8-bit BGRA or RGBA format, sRGB or not.
// view::Presenter copies the renderer's output into it so that the stored bytes stay those
// `encore render` writes: an sRGB surface gets the decoded colour and encodes it again (exact
// for 8-bit values), a linear one gets the bytes as they are. (A linear view of an sRGB surface
// would avoid the round trip, but Dawn 2026-09 aborts on surface view formats on lavapipe.)
// When the surface allows copies, the presented image can be read back (screenshots of what
// the window shows).
//
// Destroy the surface before the context's device (it unconfigures itself).

#include <webgpu/webgpu_cpp.h>

#include <cstdint>

#include "encore/core/Result.h"
#include "encore/gpu/Context.h"
#include "view/Window.h"

namespace encore::view {

// FIFO (one frame per display refresh) or the lowest-latency mode the surface supports.
enum class PresentPreference { Vsync, Uncapped };

class WindowSurface {
  public:
    static Result<WindowSurface> create(gpu::Context& context,
                                        const Window& window,
                                        PresentPreference preference);

    WindowSurface(WindowSurface&&) noexcept = default;
    WindowSurface& operator=(WindowSurface&&) noexcept;
    ~WindowSurface();

    // (Re)configures the surface for a framebuffer of this size.
    void configure(std::uint32_t width, std::uint32_t height);

    // The texture to draw the next frame into. An outdated or lost surface is configured again
    // once; fails when that does not help (or on a timeout).
    Result<wgpu::Texture> acquire();
    void present();

    wgpu::TextureFormat format() const { return mFormat; }
    // Whether format() encodes sRGB when written.
    bool srgb() const { return mSrgb; }
    wgpu::PresentMode presentMode() const { return mPresentMode; }
    // Whether the presented texture can be copied (read back for screenshots).
    bool copyable() const { return mCopyable; }
    std::uint32_t width() const { return mWidth; }
    std::uint32_t height() const { return mHeight; }

  private:
    WindowSurface() = default;
    void release();

    wgpu::Device mDevice;
    wgpu::Surface mSurface;
    wgpu::TextureFormat mFormat = wgpu::TextureFormat::Undefined;
    bool mSrgb = false;
    wgpu::PresentMode mPresentMode = wgpu::PresentMode::Fifo;
    bool mCopyable = false;
    std::uint32_t mWidth = 0;
    std::uint32_t mHeight = 0;
};

// e.g. "fifo", "immediate".
const char* presentModeName(wgpu::PresentMode mode);

}  // namespace encore::view
