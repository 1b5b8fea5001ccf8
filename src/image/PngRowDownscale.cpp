// PNGs too large to decode whole, decoded row by row with libspng's progressive decoding and
// box-filtered as the rows come (FittedDecode.h): memory for the result, one decoded row and
// three rows of sums, whatever the PNG's size.

#include <spng.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "image/FittedDecode.h"
#include "image/ImageDecoders.h"
#include "image/Srgb.h"

namespace encore::image {
namespace {

// Decoding takes the time of the full size whatever the result's: a 32768x32768 PNG (4 GiB of
// pixels) a few seconds of inflating.
constexpr std::uint32_t kMaxRowDecodedDimension = 32768;

struct SpngContextFree {
    void operator()(spng_ctx* context) const { spng_ctx_free(context); }
};

std::uint8_t toByte(double value, bool srgb) {
    value = std::clamp(value, 0.0, 1.0);
    if (srgb) {
        value = linearToSrgb(value);
    }
    return static_cast<std::uint8_t>(std::lround(value * 255.0));
}

// An area-weighted box filter fed one source row at a time, top to bottom: each source pixel adds
// its value times the part of a target pixel it covers (at most two target pixels per axis, the
// target being no larger), so every target pixel ends as the mean of the area it covers.
class RowDownscaler {
  public:
    RowDownscaler(ImageSize source, ImageSize target, PixelEncoding encoding)
        : mSource(source),
          mTarget(target),
          mSrgb(encoding == PixelEncoding::Srgb),
          mRow(std::size_t(target.width) * 4),
          mSums(std::size_t(target.width) * 4 * 2, 0.0) {
        for (int i = 0; i < 256; ++i) {
            mToLinear[i] = mSrgb ? srgbToLinear(i / 255.0) : i / 255.0;
        }
        mImage.width = target.width;
        mImage.height = target.height;
        mImage.pixels.resize(std::size_t(target.width) * target.height * 4);
    }

    void addRow(const std::uint8_t* rgba) {
        // Across: into mRow, in target pixels.
        std::fill(mRow.begin(), mRow.end(), 0.0);
        const double across = double(mTarget.width) / mSource.width;
        for (std::uint32_t x = 0; x < mSource.width; ++x) {
            spread(x, across, mTarget.width, [&](std::uint32_t tx, double weight) {
                for (int c = 0; c < 4; ++c) {
                    const std::uint8_t value = rgba[std::size_t(x) * 4 + c];
                    mRow[std::size_t(tx) * 4 + c] +=
                        weight * (c < 3 ? mToLinear[value] : value / 255.0);
                }
            });
        }
        // Down: into the one or two target rows this source row covers (rows ty kept at
        // ty % 2: every row above them is finished).
        const std::uint32_t y = mNextRow++;
        const double down = double(mTarget.height) / mSource.height;
        spread(y, down, mTarget.height, [&](std::uint32_t ty, double weight) {
            double* sums = rowSums(ty);
            for (std::size_t i = 0; i < mRow.size(); ++i) {
                sums[i] += weight * mRow[i];
            }
        });
        const double reached = (y + 1) * down;
        while (mFinished < mTarget.height && mFinished + 1 <= reached + 1e-9) {
            finishRow();
        }
    }

    ImageRgba8 finish() {
        while (mFinished < mTarget.height) {
            finishRow();
        }
        return std::move(mImage);
    }

  private:
    // Source pixel `s` spans [s, s + 1) * scale in target pixels: hands each target pixel it
    // overlaps the overlap.
    template <typename Add>
    static void spread(std::uint32_t s, double scale, std::uint32_t count, const Add& add) {
        const double begin = s * scale;
        const double end = (s + 1) * scale;
        const auto first = std::uint32_t(begin);
        for (std::uint32_t t = first; t < count && t < end; ++t) {
            const double overlap = std::min(end, t + 1.0) - std::max(begin, double(t));
            if (overlap > 0.0) {
                add(t, overlap);
            }
        }
    }

    double* rowSums(std::uint32_t targetRow) {
        return &mSums[std::size_t(targetRow % 2) * mTarget.width * 4];
    }

    // Writes the next target row out of its sums and clears them for the row after the next.
    void finishRow() {
        double* sums = rowSums(mFinished);
        std::uint8_t* out = &mImage.pixels[std::size_t(mFinished) * mTarget.width * 4];
        for (std::size_t i = 0; i < std::size_t(mTarget.width) * 4; ++i) {
            out[i] = toByte(sums[i], mSrgb && i % 4 != 3);
            sums[i] = 0.0;
        }
        ++mFinished;
    }

    ImageSize mSource;
    ImageSize mTarget;
    bool mSrgb;
    double mToLinear[256];
    std::vector<double> mRow;   // One source row filtered across.
    std::vector<double> mSums;  // Two target rows being summed.
    ImageRgba8 mImage;
    std::uint32_t mNextRow = 0;
    std::uint32_t mFinished = 0;  // Target rows written to mImage.
};

}  // namespace

Result<FittedDecode> decodeLargePngWithin(std::span<const std::uint8_t> encoded,
                                          std::uint32_t maxDimension,
                                          PixelEncoding encoding) {
    ENCORE_TRY(forEachPngChunk(encoded, [](const PngChunk&) { return true; }));
    std::unique_ptr<spng_ctx, SpngContextFree> context(spng_ctx_new(SPNG_CTX_IGNORE_ADLER32));
    if (!context) {
        return makeError(ErrorCode::LimitExceeded, "PNG decoding failed (out of memory).");
    }
    spng_set_crc_action(context.get(), SPNG_CRC_USE, SPNG_CRC_USE);
    const auto failed = [](const char* what, int code) {
        return makeError(ErrorCode::InvalidFormat,
                         std::string(what) + " (" + spng_strerror(code) + ").");
    };
    if (const int code = spng_set_png_buffer(
            context.get(), const_cast<std::uint8_t*>(encoded.data()), encoded.size())) {
        return failed("Image data is not a decodable PNG", code);
    }
    spng_ihdr ihdr{};
    if (const int code = spng_get_ihdr(context.get(), &ihdr)) {
        return failed("Image data is not a decodable PNG", code);
    }
    FittedDecode fitted;
    fitted.source = {ihdr.width, ihdr.height};
    if (ihdr.width > kMaxRowDecodedDimension || ihdr.height > kMaxRowDecodedDimension) {
        return makeError(ErrorCode::LimitExceeded, "Image size " + std::to_string(ihdr.width) +
                                                       "x" + std::to_string(ihdr.height) +
                                                       " is outside 1.." +
                                                       std::to_string(kMaxRowDecodedDimension) +
                                                       " (the PNGs Encore decodes row by row).");
    }
    const ImageSize target = fitWithin(fitted.source, maxDimension);
    ENCORE_TRY(checkDecodable({target.width, target.height, 8}));
    if (ihdr.interlace_method != 0) {
        return makeError(ErrorCode::LimitExceeded,
                         "An interlaced PNG of " + std::to_string(ihdr.width) + "x" +
                             std::to_string(ihdr.height) +
                             " is larger than Encore decodes whole and cannot be decoded row by "
                             "row.");
    }
    if (const int code = spng_decode_image(context.get(), nullptr, 0, SPNG_FMT_RGBA8,
                                           SPNG_DECODE_TRNS | SPNG_DECODE_PROGRESSIVE)) {
        return failed("PNG decoding failed", code);
    }
    RowDownscaler downscaler(fitted.source, target, encoding);
    std::vector<std::uint8_t> row(std::size_t(ihdr.width) * 4);
    for (std::uint32_t y = 0; y < ihdr.height; ++y) {
        const int code = spng_decode_row(context.get(), row.data(), row.size());
        if (code != 0 && !(code == SPNG_EOI && y + 1 == ihdr.height)) {
            return failed("PNG decoding failed", code);
        }
        downscaler.addRow(row.data());
    }
    fitted.image = downscaler.finish();
    return fitted;
}

}  // namespace encore::image
