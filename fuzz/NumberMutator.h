#pragma once

// Structure-aware mutation of glTF documents: changes a few numbers of a valid .gltf or .glb to
// boundary values. Byte-level mutation rarely yields a JSON whose numbers are all valid but one;
// these mutations keep the document valid JSON and change one to three numbers at paths the
// loader trusts (counts, offsets, lengths, strides, component types, min/max, indices of other
// objects, sparse counts, enums): 0, 1, -1, the value ±1, twice it, another number of the
// document (±1, ±4), 2^31-1, 2^32-1, 2^63, 1e300, a fraction, null (what nlohmann writes for
// NaN) or the literal text NaN, Infinity or 1e999. The document is re-serialised; a GLB gets
// its chunk and header lengths rewritten, one time in eight wrongly. Used by the libFuzzer
// target encore_fuzz_numbers and by the frame fuzzer (docs/fuzzing.md); free of libFuzzer.

#include <cstddef>
#include <cstdint>

namespace encore::fuzz {

// Mutates the `size` bytes at `data` in place (the buffer holds `maxSize` bytes) with the
// random choices of `seed`, and returns the new size. Returns 0, leaving the bytes as they were,
// when the caller should mutate them some other way (byte-level): one time in sixteen by
// choice, and for input that does not parse as glTF JSON or GLB, has no number, or whose
// mutation would not fit in `maxSize`.
std::size_t mutateNumbers(std::uint8_t* data, std::size_t size, std::size_t maxSize, unsigned seed);

// Writes into `out` (at most `maxOutSize` bytes) the first document with up to two of its
// numbers replaced by numbers found at the same keys in the second (one model's accessor count
// in another's), and returns its size; 0 when either does not parse or nothing fits.
std::size_t crossOverNumbers(const std::uint8_t* data1,
                             std::size_t size1,
                             const std::uint8_t* data2,
                             std::size_t size2,
                             std::uint8_t* out,
                             std::size_t maxOutSize,
                             unsigned seed);

}  // namespace encore::fuzz
