#pragma once

// NumPy's .npy format, version 1.0 (numpy.lib.format), written directly: a little-endian
// float64 array in C order, with the header NumPy 1.24's numpy.save writes for it (the same
// padding), so numpy.load reads it and the bytes equal numpy.save's of the same array.

#include <cstdint>
#include <span>
#include <vector>

namespace encore::batch {

// `values` (rows * columns of them, row after row) as a .npy file of shape (rows, columns).
std::vector<std::uint8_t> npyFloat64(std::span<const double> values,
                                     std::uint32_t rows,
                                     std::uint32_t columns);

}  // namespace encore::batch
