#include "view/WindowSurface.h"

#include <algorithm>
#include <span>
#include <string>

namespace encore::view {

namespace {

// The 8-bit formats Presenter can write (and gpu::readTexture read back).
bool presentable(wgpu::TextureFormat format) {
    return format == wgpu::TextureFormat::BGRA8Unorm ||
           format == wgpu::TextureFormat::BGRA8UnormSrgb ||
           format == wgpu::TextureFormat::RGBA8Unorm ||
           format == wgpu::TextureFormat::RGBA8UnormSrgb;
}

}  // namespace

const char* presentModeName(wgpu::PresentMode mode) {
    switch (mode) {
        case wgpu::PresentMode::Fifo:
            return "fifo";
        case wgpu::PresentMode::FifoRelaxed:
            return "fifo-relaxed";
        case wgpu::PresentMode::Immediate:
            return "immediate";
        case wgpu::PresentMode::Mailbox:
            return "mailbox";
        default:
            return "undefined";
    }
}

Result<WindowSurface> WindowSurface::create(gpu::Context& context,
                                            const Window& window,
                                            PresentPreference preference) {
    wgpu::SurfaceSourceXlibWindow x11;
    x11.display = window.x11Display();
    x11.window = window.x11Window();
    wgpu::SurfaceDescriptor descriptor{};
    descriptor.nextInChain = &x11;
    descriptor.label = "encore view";
    WindowSurface surface;
    surface.mDevice = context.device();
    surface.mSurface = context.instance().CreateSurface(&descriptor);
    if (!surface.mSurface) {
        return makeError(ErrorCode::DeviceError,
                         "Dawn could not create a WebGPU surface for the X11 window.");
    }
    wgpu::SurfaceCapabilities capabilities;
    if (surface.mSurface.GetCapabilities(context.adapter(), &capabilities) !=
            wgpu::Status::Success ||
        capabilities.formatCount == 0) {
        return makeError(ErrorCode::DeviceError,
                         "The adapter '" + context.adapterDescription().name +
                             "' cannot present to this window (no surface formats).");
    }
    // The first format is the surface's preference; Presenter needs an 8-bit RGBA or BGRA one.
    for (std::size_t i = 0; i < capabilities.formatCount; ++i) {
        if (presentable(capabilities.formats[i])) {
            surface.mFormat = capabilities.formats[i];
            break;
        }
    }
    if (surface.mFormat == wgpu::TextureFormat::Undefined) {
        return makeError(ErrorCode::Unsupported,
                         "The window's surface offers no 8-bit RGBA or BGRA format.");
    }
    surface.mSrgb = surface.mFormat == wgpu::TextureFormat::BGRA8UnormSrgb ||
                    surface.mFormat == wgpu::TextureFormat::RGBA8UnormSrgb;
    const std::span modes(capabilities.presentModes, capabilities.presentModeCount);
    auto supports = [&](wgpu::PresentMode mode) {
        return std::find(modes.begin(), modes.end(), mode) != modes.end();
    };
    surface.mPresentMode = wgpu::PresentMode::Fifo;  // Every surface supports FIFO.
    if (preference == PresentPreference::Uncapped) {
        for (auto mode : {wgpu::PresentMode::Immediate, wgpu::PresentMode::Mailbox,
                          wgpu::PresentMode::FifoRelaxed}) {
            if (supports(mode)) {
                surface.mPresentMode = mode;
                break;
            }
        }
    }
    surface.mCopyable =
        (capabilities.usages & wgpu::TextureUsage::CopySrc) != wgpu::TextureUsage::None;
    const auto [width, height] = window.framebufferSize();
    surface.configure(width, height);
    return surface;
}

WindowSurface& WindowSurface::operator=(WindowSurface&& other) noexcept {
    if (this != &other) {
        release();
        mDevice = std::move(other.mDevice);
        mSurface = std::move(other.mSurface);
        mFormat = other.mFormat;
        mSrgb = other.mSrgb;
        mPresentMode = other.mPresentMode;
        mCopyable = other.mCopyable;
        mWidth = other.mWidth;
        mHeight = other.mHeight;
    }
    return *this;
}

WindowSurface::~WindowSurface() {
    release();
}

void WindowSurface::release() {
    if (mSurface && mWidth > 0) {
        // Dawn's surface keeps a swap chain of the device; detach it while the device lives.
        mSurface.Unconfigure();
    }
    mSurface = nullptr;
}

void WindowSurface::configure(std::uint32_t width, std::uint32_t height) {
    mWidth = std::max<std::uint32_t>(width, 1);
    mHeight = std::max<std::uint32_t>(height, 1);
    wgpu::SurfaceConfiguration configuration{};
    configuration.device = mDevice;
    configuration.format = mFormat;
    configuration.usage = wgpu::TextureUsage::RenderAttachment;
    if (mCopyable) {
        configuration.usage |= wgpu::TextureUsage::CopySrc;
    }
    configuration.width = mWidth;
    configuration.height = mHeight;
    configuration.alphaMode = wgpu::CompositeAlphaMode::Auto;
    configuration.presentMode = mPresentMode;
    mSurface.Configure(&configuration);
}

Result<wgpu::Texture> WindowSurface::acquire() {
    for (int attempt = 0; attempt < 2; ++attempt) {
        wgpu::SurfaceTexture texture;
        mSurface.GetCurrentTexture(&texture);
        switch (texture.status) {
            case wgpu::SurfaceGetCurrentTextureStatus::SuccessOptimal:
            case wgpu::SurfaceGetCurrentTextureStatus::SuccessSuboptimal:
                return texture.texture;
            case wgpu::SurfaceGetCurrentTextureStatus::Outdated:
            case wgpu::SurfaceGetCurrentTextureStatus::Lost:
                configure(mWidth, mHeight);
                break;
            default:
                return makeError(ErrorCode::DeviceError,
                                 "The window's surface gave no texture to draw into (status " +
                                     std::to_string(int(texture.status)) + ").");
        }
    }
    return makeError(ErrorCode::DeviceError,
                     "The window's surface stays outdated after configuring it again.");
}

void WindowSurface::present() {
    mSurface.Present();
}

}  // namespace encore::view
