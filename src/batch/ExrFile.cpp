#include "batch/ExrFile.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfOutputFile.h>
#include <half.h>

#include <cstring>
#include <exception>
#include <string>

namespace encore::batch {
namespace {

// An Imf::OStream into a byte vector.
class MemoryStream : public Imf::OStream {
  public:
    MemoryStream() : Imf::OStream("memory") {}

    void write(const char c[], int n) override {
        const std::size_t end = mPosition + std::size_t(n);
        if (end > mBytes.size()) {
            mBytes.resize(end);
        }
        std::memcpy(mBytes.data() + mPosition, c, std::size_t(n));
        mPosition = end;
    }
    std::uint64_t tellp() override { return mPosition; }
    void seekp(std::uint64_t position) override { mPosition = position; }

    std::vector<std::uint8_t> take() { return std::move(mBytes); }

  private:
    std::vector<std::uint8_t> mBytes;
    std::size_t mPosition = 0;
};

Error exrError(const std::exception& error) {
    return Error{ErrorCode::IoError,
                 std::string("OpenEXR could not write the image: ") + error.what()};
}

}  // namespace

Result<std::vector<std::uint8_t>> encodeExrDepth(std::span<const float> depth,
                                                 std::uint32_t width,
                                                 std::uint32_t height) {
    if (depth.size() != std::size_t(width) * height || width == 0 || height == 0) {
        return makeError(ErrorCode::InvalidArgument,
                         "An EXR depth image needs width x height "
                         "values and at least one pixel.");
    }
    try {
        Imf::Header header{int(width), int(height)};
        header.compression() = Imf::ZIP_COMPRESSION;
        header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
        Imf::FrameBuffer frame;
        frame.insert("Z", Imf::Slice(Imf::FLOAT,
                                     const_cast<char*>(reinterpret_cast<const char*>(depth.data())),
                                     sizeof(float), sizeof(float) * width));
        MemoryStream stream;
        {
            Imf::OutputFile file(stream, header);
            file.setFrameBuffer(frame);
            file.writePixels(int(height));
        }  // The destructor finishes the file (its line offsets).
        return stream.take();
    } catch (const std::exception& error) {
        return exrError(error);
    }
}

Result<std::vector<std::uint8_t>> encodeExrRgbaHalf(std::span<const float> rgba,
                                                    std::uint32_t width,
                                                    std::uint32_t height) {
    if (rgba.size() != std::size_t(width) * height * 4 || width == 0 || height == 0) {
        return makeError(ErrorCode::InvalidArgument,
                         "An EXR RGBA image needs width x height x 4 "
                         "values and at least one pixel.");
    }
    std::vector<half> halves(rgba.size());
    for (std::size_t i = 0; i < rgba.size(); ++i) {
        halves[i] = half(rgba[i]);
    }
    try {
        Imf::Header header{int(width), int(height)};
        header.compression() = Imf::ZIP_COMPRESSION;
        Imf::FrameBuffer frame;
        const char* names[] = {"R", "G", "B", "A"};
        for (std::size_t channel = 0; channel < 4; ++channel) {
            header.channels().insert(names[channel], Imf::Channel(Imf::HALF));
            frame.insert(names[channel],
                         Imf::Slice(Imf::HALF, reinterpret_cast<char*>(halves.data() + channel),
                                    sizeof(half) * 4, sizeof(half) * 4 * width));
        }
        MemoryStream stream;
        {
            Imf::OutputFile file(stream, header);
            file.setFrameBuffer(frame);
            file.writePixels(int(height));
        }
        return stream.take();
    } catch (const std::exception& error) {
        return exrError(error);
    }
}

}  // namespace encore::batch
