#pragma once

// The visibility strategy's scene-sized working buffers: the culled units, the hardware path's
// triangle list, the workgroup raster's blocks and records, and the shading bins. Every frame
// writes them before it reads them (the unit table at the start of the units buffer,
// VisibilityTables::unitTable, when its scene is prepared), so no scene's contents matter to
// the next: a renderer that prepares scene after scene (encore batch) keeps them
// (KeptStrategyObjects) and makes one again only when a scene needs more. On the H100 making and
// freeing them (tens of megabytes, a dedicated allocation each) cost about 3 ms of the device
// thread per dense model.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>

namespace encore::render {

struct VisibilityWorkBuffers {
    // Bytes each buffer must hold for a scene.
    struct Sizes {
        std::uint64_t units = 0;
        std::uint64_t hardwareList = 0;
        std::uint64_t workgroupList = 0;
        std::uint64_t bins = 0;
    };

    // Makes every buffer smaller than `sizes` asks (never smaller than 4 bytes) at that size;
    // keeps the others, larger ones included.
    void ensure(const wgpu::Device& device, const Sizes& sizes);

    wgpu::Buffer units;
    wgpu::Buffer hardwareList;
    wgpu::Buffer workgroupList;  // Blocks, then records (visibility_raster.wgsl).
    wgpu::Buffer bins;           // Cleared per frame: the scene's part only.
};

}  // namespace encore::render
