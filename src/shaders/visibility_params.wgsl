// The parameters of one view of the visibility strategy (VisibilityStrategy.cpp's ViewParams):
// a uniform bound with a dynamic offset per view.
struct VisibilityParams {
    itemCount: u32,
    targetWidth: u32,
    // The view's viewport in target pixels.
    viewportX: u32,
    viewportY: u32,
    viewportWidth: u32,
    viewportHeight: u32,
    // Triangles whose screen bounds span at most maxComputePixels each way are rasterised by one
    // thread, up to maxWorkgroupPixels by a workgroup in tiles; larger ones by the hardware.
    maxComputePixels: f32,
    frustumTest: u32,  // 0 in multi-view frames, whose views each frame the whole scene.
    hardwareCapacity: u32,
    // The binning's first bin (visibility_bins.wgsl): each dispatch lists kRoundBins from it.
    firstBin: u32,
    maxWorkgroupPixels: f32,
    // Visibility samples per pixel (1, or 4 at the standard 4x positions): the visibility buffer
    // holds `samples` entries per pixel, pixel-major (visibility_samples.wgsl).
    samples: u32,
    // The workgroup list: blocks in its first workgroupBlocks entries, then workgroupRecords
    // triangle records (visibility_raster.wgsl).
    workgroupBlocks: u32,
    workgroupRecords: u32,
    // 1 where maxWorkgroupPixels is at its largest: the compute raster takes every triangle,
    // clipping those that cross the near or far plane or span more than it (workgroupMain), and
    // the hardware pass is not drawn.
    computeTakesAll: u32,
}
