// JPEG decoding with libjpeg-turbo: on 2048x2048 progressive textures it takes about 70% of
// stb_image's time. Its IDCT and upsampling round differently from stb's, by at most 3 levels
// on the shared models' JPEGs.
//
// libjpeg reports errors by calling error_exit, whose default prints and calls exit(). Here it
// formats the message and longjmps back to the stage that called into libjpeg. longjmp skips
// destructors, so each stage is a function of its own whose frame holds nothing that needs one;
// the caller's objects (the output pixels, the decompressor's cleanup) live outside it.

// jpeglib.h uses size_t and FILE without including their headers.
#include <cstdio>

#include <jpeglib.h>

#include <algorithm>
#include <csetjmp>
#include <string>

#include "image/ImageDecoders.h"

namespace encore::image {
namespace {

// A progressive JPEG may declare any number of scans, each a pass over all coefficients: a few
// kilobytes can keep a decoder busy for minutes. libjpeg-turbo's documentation suggests this
// limit (real progressive files have about ten scans).
constexpr int kMaxJpegScans = 500;

struct JpegErrors {
    jpeg_error_mgr manager;  // First: libjpeg hands back a pointer to it.
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX] = {};
};

[[noreturn]] void failDecoding(j_common_ptr info) {
    auto* errors = reinterpret_cast<JpegErrors*>(info->err);
    errors->manager.format_message(info, errors->message);
    std::longjmp(errors->jump, 1);
}

// Warnings (corrupt data that libjpeg recovers from, such as extraneous bytes between markers)
// are what stb_image accepted silently too: the image decodes, and nothing is printed.
void ignoreMessage(j_common_ptr, int) {}

void limitScans(j_common_ptr info) {
    auto* decompress = reinterpret_cast<j_decompress_ptr>(info);
    if (decompress->input_scan_number > kMaxJpegScans) {
        auto* errors = reinterpret_cast<JpegErrors*>(info->err);
        std::snprintf(errors->message, sizeof(errors->message), "more than %d progressive scans",
                      kMaxJpegScans);
        std::longjmp(errors->jump, 1);
    }
}

struct Decompressor {
    jpeg_decompress_struct info{};
    JpegErrors errors;
    jpeg_progress_mgr progress{};

    Decompressor() {
        info.err = jpeg_std_error(&errors.manager);
        errors.manager.error_exit = failDecoding;
        errors.manager.emit_message = ignoreMessage;
        progress.progress_monitor = limitScans;
    }
    ~Decompressor() { jpeg_destroy_decompress(&info); }
    Decompressor(const Decompressor&) = delete;
    Decompressor& operator=(const Decompressor&) = delete;
};

// The stages below return false after a libjpeg error, whose text is in errors.message.

bool readHeader(Decompressor& jpeg, std::span<const std::uint8_t> encoded) {
    if (setjmp(jpeg.errors.jump)) {
        return false;
    }
    jpeg_create_decompress(&jpeg.info);
    jpeg.info.progress = &jpeg.progress;
    jpeg_mem_src(&jpeg.info, encoded.data(), static_cast<unsigned long>(encoded.size()));
    jpeg_read_header(&jpeg.info, TRUE);
    return true;
}

bool decompressInto(Decompressor& jpeg, std::uint8_t* pixels) {
    if (setjmp(jpeg.errors.jump)) {
        return false;
    }
    jpeg.info.out_color_space = JCS_EXT_RGBA;
    jpeg_start_decompress(&jpeg.info);
    const std::size_t rowBytes = std::size_t(jpeg.info.output_width) * 4;
    while (jpeg.info.output_scanline < jpeg.info.output_height) {
        JSAMPROW row = pixels + std::size_t(jpeg.info.output_scanline) * rowBytes;
        jpeg_read_scanlines(&jpeg.info, &row, 1);
    }
    jpeg_finish_decompress(&jpeg.info);
    return true;
}

bool calcOutputSize(Decompressor& jpeg) {
    if (setjmp(jpeg.errors.jump)) {
        return false;
    }
    jpeg_calc_output_dimensions(&jpeg.info);
    return true;
}

Error jpegError(const char* what, const Decompressor& jpeg) {
    return makeError(ErrorCode::InvalidFormat,
                     std::string(what) + " (" + jpeg.errors.message + ").");
}

}  // namespace

bool isJpeg(std::span<const std::uint8_t> encoded) {
    return encoded.size() >= 3 && encoded[0] == 0xff && encoded[1] == 0xd8 && encoded[2] == 0xff;
}

Result<ImageRgba8> decodeJpeg(std::span<const std::uint8_t> encoded, std::uint32_t maxDimension) {
    Decompressor jpeg;
    if (!readHeader(jpeg, encoded)) {
        return jpegError("Image data is not a decodable JPEG", jpeg);
    }
    if (jpeg.info.jpeg_color_space == JCS_CMYK || jpeg.info.jpeg_color_space == JCS_YCCK) {
        return decodeWithStb(encoded);
    }
    const ImageHeader source{jpeg.info.image_width, jpeg.info.image_height, 8};
    // A baseline JPEG decodes at 1/2, 1/4 or 1/8 of its size for the cost of that size (the
    // IDCT skips the frequencies it drops): the largest of those still no smaller than the size
    // wanted, which the box filter then reaches. A progressive one keeps every coefficient of
    // the full size in memory whatever the scale: it must fit the limits as it is.
    if (maxDimension > 0 && !jpeg_has_multiple_scans(&jpeg.info)) {
        const std::uint32_t longest = std::max(source.width, source.height);
        unsigned denominator = 1;
        while (denominator < 8 && longest / (denominator * 2) >= maxDimension) {
            denominator *= 2;
        }
        jpeg.info.scale_num = 1;
        jpeg.info.scale_denom = denominator;
        if (!calcOutputSize(jpeg)) {
            return jpegError("JPEG decoding failed", jpeg);
        }
    } else {
        ENCORE_TRY(checkDecodable(source));
        jpeg.info.output_width = source.width;
        jpeg.info.output_height = source.height;
    }
    ENCORE_TRY(checkDecodable({jpeg.info.output_width, jpeg.info.output_height, 8}));
    ImageRgba8 image;
    image.width = jpeg.info.output_width;
    image.height = jpeg.info.output_height;
    image.pixels.resize(std::size_t(image.width) * image.height * 4);
    if (!decompressInto(jpeg, image.pixels.data())) {
        return jpegError("JPEG decoding failed", jpeg);
    }
    return image;
}

}  // namespace encore::image
