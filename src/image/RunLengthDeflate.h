#pragma once

// Fast zlib compression for PNG image data (ImageCodec's PngCompression::Fast): one deflate
// block with a Huffman code fitted to the data and runs of a repeated byte as its only matches.

#include <cstddef>
#include <cstdint>
#include <span>

namespace encore::image {

// The most bytes runLengthZlib writes for `size` bytes of data.
std::size_t runLengthZlibBound(std::size_t size);
// Writes a complete zlib stream (header, deflate data, Adler-32) of `data` to `out`, which has
// room for runLengthZlibBound(data.size()) bytes; returns the bytes written.
std::size_t runLengthZlib(std::span<const std::uint8_t> data, std::uint8_t* out);

}  // namespace encore::image
