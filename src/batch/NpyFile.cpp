#include "batch/NpyFile.h"

#include <bit>
#include <cstring>
#include <string>

namespace encore::batch {
namespace {

// numpy.lib.format: the magic string with the version, the header padded so the data starts on
// a multiple of 64 bytes, and room in the header for the first axis to grow to 21 digits.
constexpr char kMagic[] = "\x93NUMPY\x01\x00";
constexpr std::size_t kMagicSize = 8;
constexpr std::size_t kAlignment = 64;
constexpr std::size_t kGrowthAxisDigits = 21;

}  // namespace

std::vector<std::uint8_t> npyFloat64(std::span<const double> values,
                                     std::uint32_t rows,
                                     std::uint32_t columns) {
    static_assert(std::endian::native == std::endian::little, "'<f8' is little-endian");
    const std::string first = std::to_string(rows);
    std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': (" + first + ", " +
                         std::to_string(columns) + "), }";
    header.append(kGrowthAxisDigits - first.size(), ' ');
    // The header ends with a newline; spaces before it make the total a multiple of 64.
    const std::size_t unpadded = kMagicSize + 2 + header.size() + 1;
    header.append(kAlignment - unpadded % kAlignment, ' ');
    header += '\n';

    std::vector<std::uint8_t> file(kMagicSize + 2 + header.size() + values.size() * sizeof(double));
    std::memcpy(file.data(), kMagic, kMagicSize);
    file[kMagicSize] = std::uint8_t(header.size() & 0xff);
    file[kMagicSize + 1] = std::uint8_t(header.size() >> 8);
    std::memcpy(file.data() + kMagicSize + 2, header.data(), header.size());
    if (!values.empty()) {
        std::memcpy(file.data() + kMagicSize + 2 + header.size(), values.data(),
                    values.size() * sizeof(double));
    }
    return file;
}

}  // namespace encore::batch
