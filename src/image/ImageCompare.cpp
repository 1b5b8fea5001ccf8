#include "image/ImageCompare.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

namespace encore::image {
namespace {

constexpr int kSsimWindow = 11;
constexpr double kSsimSigma = 1.5;
constexpr double kSsimC1 = (0.01 * 255.0) * (0.01 * 255.0);
constexpr double kSsimC2 = (0.03 * 255.0) * (0.03 * 255.0);

std::string sizeText(const ImageRgba8& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height);
}

bool consistent(const ImageRgba8& image) {
    return image.width > 0 && image.height > 0 &&
           image.pixels.size() == std::size_t(image.width) * image.height * 4;
}

Result<void> checkComparable(const ImageRgba8& a, const ImageRgba8& b) {
    if (!consistent(a) || !consistent(b)) {
        return makeError(ErrorCode::InvalidArgument,
                         "Cannot compare an empty or inconsistent image (" + sizeText(a) + " and " +
                             sizeText(b) + ").");
    }
    if (a.width != b.width || a.height != b.height) {
        return makeError(ErrorCode::InvalidArgument, "Cannot compare images of different sizes (" +
                                                         sizeText(a) + " and " + sizeText(b) +
                                                         ").");
    }
    return {};
}

// The 2D window is the outer product of this normalised 1D Gaussian with itself, which is
// exactly the normalised 2D Gaussian, so the image can be filtered one axis at a time.
std::vector<double> gaussianKernel(int size) {
    std::vector<double> kernel(std::size_t(size), 0.0);
    const int radius = size / 2;
    double sum = 0.0;
    for (int i = 0; i < size; ++i) {
        const double x = i - radius;
        kernel[std::size_t(i)] = std::exp(-x * x / (2.0 * kSsimSigma * kSsimSigma));
        sum += kernel[std::size_t(i)];
    }
    for (double& weight : kernel) {
        weight /= sum;
    }
    return kernel;
}

double luma(const std::uint8_t* pixel) {
    return 0.2126 * pixel[0] + 0.7152 * pixel[1] + 0.0722 * pixel[2];
}

// The five local statistics SSIM needs, each filtered horizontally over one image row.
struct FilteredRow {
    std::vector<double> a, b, aa, bb, ab;

    explicit FilteredRow(std::size_t width) : a(width), b(width), aa(width), bb(width), ab(width) {}
};

void filterRow(const ImageRgba8& imageA,
               const ImageRgba8& imageB,
               std::uint32_t y,
               const std::vector<double>& kernel,
               std::vector<double>& lumaA,
               std::vector<double>& lumaB,
               FilteredRow& out) {
    for (std::uint32_t x = 0; x < imageA.width; ++x) {
        lumaA[x] = luma(imageA.pixel(x, y));
        lumaB[x] = luma(imageB.pixel(x, y));
    }
    for (std::size_t x = 0; x < out.a.size(); ++x) {
        double a = 0.0, b = 0.0, aa = 0.0, bb = 0.0, ab = 0.0;
        for (std::size_t i = 0; i < kernel.size(); ++i) {
            const double k = kernel[i];
            const double pa = lumaA[x + i];
            const double pb = lumaB[x + i];
            a += k * pa;
            b += k * pb;
            aa += k * pa * pa;
            bb += k * pb * pb;
            ab += k * pa * pb;
        }
        out.a[x] = a;
        out.b[x] = b;
        out.aa[x] = aa;
        out.bb[x] = bb;
        out.ab[x] = ab;
    }
}

}  // namespace

Result<SsimMap> ssimLuminanceMap(const ImageRgba8& a, const ImageRgba8& b) {
    ENCORE_TRY(checkComparable(a, b));
    int window = std::min<int>(kSsimWindow, int(std::min(a.width, a.height)));
    window -= (window % 2 == 0) ? 1 : 0;  // An odd window keeps its centre on a pixel.
    const std::vector<double> kernel = gaussianKernel(window);

    SsimMap map;
    map.width = a.width - std::uint32_t(window) + 1;
    map.height = a.height - std::uint32_t(window) + 1;
    map.values.resize(std::size_t(map.width) * map.height);

    // Horizontally filtered rows kept in a ring of `window` rows: memory stays proportional to
    // the width rather than to the image (SSIM of large renders would otherwise need ~40 bytes
    // of temporaries per pixel).
    std::vector<FilteredRow> ring(std::size_t(window), FilteredRow(map.width));
    std::vector<double> lumaA(a.width), lumaB(a.width);
    for (int row = 0; row < window - 1; ++row) {
        filterRow(a, b, std::uint32_t(row), kernel, lumaA, lumaB, ring[std::size_t(row)]);
    }
    double sum = 0.0;
    for (std::uint32_t y = 0; y < map.height; ++y) {
        const std::uint32_t newest = y + std::uint32_t(window) - 1;
        filterRow(a, b, newest, kernel, lumaA, lumaB, ring[newest % std::uint32_t(window)]);
        for (std::uint32_t x = 0; x < map.width; ++x) {
            double muA = 0.0, muB = 0.0, aa = 0.0, bb = 0.0, ab = 0.0;
            for (int i = 0; i < window; ++i) {
                const FilteredRow& row = ring[(y + std::uint32_t(i)) % std::uint32_t(window)];
                const double k = kernel[std::size_t(i)];
                muA += k * row.a[x];
                muB += k * row.b[x];
                aa += k * row.aa[x];
                bb += k * row.bb[x];
                ab += k * row.ab[x];
            }
            const double varianceA = aa - muA * muA;
            const double varianceB = bb - muB * muB;
            const double covariance = ab - muA * muB;
            const double value =
                ((2.0 * muA * muB + kSsimC1) * (2.0 * covariance + kSsimC2)) /
                ((muA * muA + muB * muB + kSsimC1) * (varianceA + varianceB + kSsimC2));
            map.values[std::size_t(y) * map.width + x] = float(value);
            sum += value;
        }
    }
    map.mean = sum / double(map.values.size());
    return map;
}

Result<double> ssimLuminance(const ImageRgba8& a, const ImageRgba8& b) {
    ENCORE_TRY_ASSIGN(auto map, ssimLuminanceMap(a, b));
    return map.mean;
}

Result<ColorError> colorError(const ImageRgba8& a, const ImageRgba8& b) {
    ENCORE_TRY(checkComparable(a, b));
    std::uint64_t sum = 0;
    std::uint64_t over = 0;
    int largest = 0;
    const std::size_t count = std::size_t(a.width) * a.height;
    for (std::size_t i = 0; i < count; ++i) {
        int pixelLargest = 0;
        for (std::size_t c = 0; c < 3; ++c) {
            const int difference = std::abs(int(a.pixels[i * 4 + c]) - int(b.pixels[i * 4 + c]));
            sum += std::uint64_t(difference);
            pixelLargest = std::max(pixelLargest, difference);
        }
        largest = std::max(largest, pixelLargest);
        over += pixelLargest > kColorErrorThreshold ? 1 : 0;
    }
    ColorError error;
    error.meanAbsolute = double(sum) / (3.0 * double(count));
    error.maxAbsolute = largest;
    error.fractionOverThreshold = double(over) / double(count);
    return error;
}

ImageRgba8 differenceImage(const ImageRgba8& a, const ImageRgba8& b, float gain) {
    ImageRgba8 difference;
    if (!consistent(a) || !consistent(b)) {
        return difference;
    }
    difference.width = std::min(a.width, b.width);
    difference.height = std::min(a.height, b.height);
    difference.pixels.resize(std::size_t(difference.width) * difference.height * 4);
    for (std::uint32_t y = 0; y < difference.height; ++y) {
        for (std::uint32_t x = 0; x < difference.width; ++x) {
            const std::uint8_t* pa = a.pixel(x, y);
            const std::uint8_t* pb = b.pixel(x, y);
            std::uint8_t* out = difference.pixel(x, y);
            for (int c = 0; c < 3; ++c) {
                const float scaled = std::round(float(std::abs(int(pa[c]) - int(pb[c]))) * gain);
                // Written so that a NaN gain gives 0 rather than an undefined conversion.
                out[c] = scaled > 0.0f ? std::uint8_t(std::min(scaled, 255.0f)) : 0;
            }
            out[3] = 255;
        }
    }
    return difference;
}

ImageRgba8 sideBySide(std::span<const ImageRgba8> images, std::uint32_t gap) {
    ImageRgba8 row;
    if (images.empty()) {
        return row;
    }
    for (std::size_t i = 0; i < images.size(); ++i) {
        row.width += images[i].width + (i > 0 ? gap : 0);
        row.height = std::max(row.height, images[i].height);
    }
    if (row.width == 0 || row.height == 0) {
        return ImageRgba8{};
    }
    row.pixels.assign(std::size_t(row.width) * row.height * 4, kSideBySideGrey);
    std::uint32_t left = 0;
    for (const ImageRgba8& image : images) {
        if (consistent(image)) {
            for (std::uint32_t y = 0; y < image.height; ++y) {
                std::copy_n(image.pixel(0, y), std::size_t(image.width) * 4, row.pixel(left, y));
            }
        }
        left += image.width + gap;
    }
    for (std::size_t i = 3; i < row.pixels.size(); i += 4) {
        row.pixels[i] = 255;
    }
    return row;
}

}  // namespace encore::image
