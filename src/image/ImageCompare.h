#pragma once

// Comparing two RGBA8 images: structural similarity (SSIM) of their luma, per-pixel colour
// error, and pictures that show where they differ. CPU only; used by `encore compare` and by
// tests that check renders against references.

#include <cstdint>
#include <span>
#include <vector>

#include "encore/core/Result.h"
#include "encore/image/ImageCodec.h"

namespace encore::image {

// SSIM as Wang, Bovik, Sheikh and Simoncelli define it ("Image quality assessment: from error
// visibility to structural similarity", 2004): an 11x11 Gaussian window (sigma 1.5, normalised),
// K1 = 0.01, K2 = 0.03, L = 255, evaluated at every position where the window lies wholly
// inside the image (no padding, no downsampling). The signal is the luma
// Y = 0.2126 R + 0.7152 G + 0.0722 B of the stored 8-bit values (sRGB-encoded, not linearised);
// alpha is ignored. Images narrower or shorter than 11 pixels use the largest odd window that
// fits (same sigma, renormalised), so that any two images of equal size can be compared.
struct SsimMap {
    double mean = 0.0;        // The mean SSIM: 1 for identical images, near 0 for unrelated ones.
    std::uint32_t width = 0;  // Image width - window + 1.
    std::uint32_t height = 0;
    std::vector<float> values;  // width * height local SSIM values, rows top to bottom; the value
                                // at (x, y) is that of the window whose top-left pixel is (x, y).
};

// The mean SSIM of the two images' luma. Fails (InvalidArgument) when the sizes differ or an
// image is empty or inconsistent (pixels.size() != width * height * 4).
Result<double> ssimLuminance(const ImageRgba8& a, const ImageRgba8& b);

// The same computation, also returning the local SSIM values (they are computed anyway).
Result<SsimMap> ssimLuminanceMap(const ImageRgba8& a, const ImageRgba8& b);

// A pixel counts as differing when one of its colour channels differs by more than this.
inline constexpr int kColorErrorThreshold = 16;

// Absolute differences of the R, G and B values (0..255); alpha is ignored.
struct ColorError {
    double meanAbsolute = 0.0;           // Mean over all pixels and the three channels.
    int maxAbsolute = 0;                 // Largest difference of any channel of any pixel.
    double fractionOverThreshold = 0.0;  // Pixels whose largest channel difference exceeds
                                         // kColorErrorThreshold, over all pixels (0..1).
};

// Fails like ssimLuminance.
Result<ColorError> colorError(const ImageRgba8& a, const ImageRgba8& b);

// |a - b| per colour channel times `gain`, rounded and clamped to 0..255, alpha 255. The images
// should have the same size; otherwise the result covers their common top-left area (empty
// when one is empty).
ImageRgba8 differenceImage(const ImageRgba8& a, const ImageRgba8& b, float gain);

// The grey of the gaps between images and of the area below shorter images in sideBySide.
inline constexpr std::uint8_t kSideBySideGrey = 128;

// The images in a row from left to right, top-aligned, `gap` pixels apart; the gaps and the area
// below shorter images are kSideBySideGrey. Every pixel is opaque. No images: an empty image.
ImageRgba8 sideBySide(std::span<const ImageRgba8> images, std::uint32_t gap = 4);

}  // namespace encore::image
