// One shading bin's record: 256 bytes (WebGPU's storage offset alignment), so that the shading
// pass binds each bin's with a dynamic offset. render/VisibilityStrategy.cpp's kBinStride.
const kBinPaddingWords = 60u;
// Bins listed per binning dispatch, from VisibilityParams.firstBin: VisibilityTarget's kRoundBins.
const kRoundBins = 64u;
