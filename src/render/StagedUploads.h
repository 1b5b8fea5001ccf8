#pragma once

// What `encore batch` copies into staging buffers on other threads ahead of Renderer::prepare:
// the scene's images (render/StagedImages.h) and its shared geometry (render/StagedGeometry.h);
// either may be null, and the renderer then uploads that part itself.

namespace encore::render {

class StagedImages;
class StagedGeometry;

struct StagedUploads {
    StagedImages* images = nullptr;
    StagedGeometry* geometry = nullptr;
};

}  // namespace encore::render
