#pragma once

// The viewer's on-screen overlay: text (stb_easy_font's quads), filled rectangles and lines,
// collected on the CPU each frame in window pixels and drawn in a pass of their own over the
// presented image (overlay.wgsl), so the scene's passes and bundles never change for it.
//
// Why not Dear ImGui: Debian bookworm's 1.86 has a WebGPU backend written against the WebGPU
// API of 2021, which today's Dawn (sid) no longer accepts, and an overlay of a few lines of
// text and two graphs needs none of ImGui's widgets. stb_easy_font is already in libstb-dev.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "encore/core/Result.h"
#include "shaders/ShaderLibrary.h"

namespace encore::view {

// Straight-alpha RGBA, 0..255, packed as bytes in memory order.
struct OverlayColor {
    std::uint8_t r = 255, g = 255, b = 255, a = 255;
};

class Overlay {
  public:
    static Result<Overlay> create(const wgpu::Device& device,
                                  const wgpu::Queue& queue,
                                  shaders::ShaderLibrary& shaders,
                                  wgpu::TextureFormat surfaceFormat);

    // Starts a new frame's overlay (forgets what was added before).
    void clear() { mVertices.clear(); }
    // Text with its top left at (x, y); `scale` multiplies stb_easy_font's 6-pixel-high glyphs.
    // Lines break at '\n'. Returns the text's width and height in pixels.
    glm::vec2 addText(float x,
                      float y,
                      std::string_view text,
                      OverlayColor color,
                      float scale = 2.0f);
    static glm::vec2 measureText(std::string_view text, float scale = 2.0f);
    void addRectangle(float x, float y, float width, float height, OverlayColor color);
    void addLine(glm::vec2 from, glm::vec2 to, float thickness, OverlayColor color);

    // Draws what was added into `target` (a `width` x `height` view of the surface format),
    // over its contents. Nothing is recorded when nothing was added.
    void encode(const wgpu::CommandEncoder& commands,
                const wgpu::TextureView& target,
                std::uint32_t width,
                std::uint32_t height);

    std::size_t vertexCount() const { return mVertices.size(); }

  private:
    struct Vertex {
        float x, y;
        OverlayColor color;
    };
    static_assert(sizeof(Vertex) == 12);
    Overlay() = default;
    void addQuad(const glm::vec2 corners[4], OverlayColor color);

    wgpu::Device mDevice;
    wgpu::Queue mQueue;
    wgpu::RenderPipeline mPipeline;
    wgpu::Buffer mViewport;
    wgpu::BindGroup mBindGroup;
    wgpu::Buffer mVertexBuffer;
    std::uint64_t mVertexCapacity = 0;
    std::vector<Vertex> mVertices;
};

}  // namespace encore::view
