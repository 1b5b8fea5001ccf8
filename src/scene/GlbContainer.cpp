// GLB framing: a 12-byte header, a JSON chunk, then an optional BIN chunk. Every length comes
// from the file, so each is checked against the bytes actually present before it is used.

#include <cstdio>
#include <cstring>

#include "scene/LoadContext.h"

namespace encore::scene {
namespace {

constexpr std::uint32_t kGlbMagic = 0x46546C67;   // "glTF"
constexpr std::uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;   // "BIN\0"
constexpr std::size_t kHeaderSize = 12;
constexpr std::size_t kChunkHeaderSize = 8;

std::uint32_t readU32(std::span<const std::uint8_t> bytes, std::size_t offset) {
    // GLB is little-endian, like every platform Encore targets.
    std::uint32_t value = 0;
    std::memcpy(&value, bytes.data() + offset, sizeof(value));
    return value;
}

std::string hex(std::uint32_t value) {
    char text[16];
    std::snprintf(text, sizeof(text), "0x%08X", value);
    return text;
}

}  // namespace

bool hasGlbMagic(std::span<const std::uint8_t> bytes) {
    return bytes.size() >= 4 && readU32(bytes, 0) == kGlbMagic;
}

Result<GlbChunks> parseGlb(std::span<const std::uint8_t> bytes) {
    if (bytes.size() < kHeaderSize) {
        return makeError(ErrorCode::InvalidFormat, "The GLB file is too short for its header (" +
                                                       std::to_string(bytes.size()) + " bytes).");
    }
    if (readU32(bytes, 0) != kGlbMagic) {
        return makeError(ErrorCode::InvalidFormat,
                         "The file does not start with the GLB magic "
                         "'glTF' (found " +
                             hex(readU32(bytes, 0)) + ").");
    }
    const std::uint32_t version = readU32(bytes, 4);
    if (version != 2) {
        return makeError(ErrorCode::Unsupported, "The GLB container version (" +
                                                     std::to_string(version) +
                                                     ") is not supported; Encore reads version 2.");
    }
    const std::uint32_t totalLength = readU32(bytes, 8);
    if (totalLength > bytes.size() || totalLength < kHeaderSize) {
        return makeError(ErrorCode::InvalidFormat, "The GLB header's length (" +
                                                       std::to_string(totalLength) +
                                                       " bytes) does not match the file (" +
                                                       std::to_string(bytes.size()) + " bytes).");
    }
    const auto file = bytes.first(totalLength);

    GlbChunks chunks;
    bool haveJson = false;
    std::size_t offset = kHeaderSize;
    for (std::size_t chunkIndex = 0; offset < file.size(); ++chunkIndex) {
        if (file.size() - offset < kChunkHeaderSize) {
            return makeError(ErrorCode::InvalidFormat,
                             "GLB chunk " + std::to_string(chunkIndex) + " header at offset " +
                                 std::to_string(offset) + " is cut off by the end of the file (" +
                                 std::to_string(file.size()) + " bytes).");
        }
        const std::uint32_t length = readU32(file, offset);
        const std::uint32_t type = readU32(file, offset + 4);
        const std::size_t dataOffset = offset + kChunkHeaderSize;
        if (length > file.size() - dataOffset) {
            return makeError(ErrorCode::InvalidFormat,
                             "GLB chunk " + std::to_string(chunkIndex) + " (length " +
                                 std::to_string(length) + " at offset " +
                                 std::to_string(dataOffset) +
                                 ") extends past the end of the file (" +
                                 std::to_string(file.size()) + " bytes).");
        }
        const auto data = file.subspan(dataOffset, length);
        if (chunkIndex == 0) {
            if (type != kChunkJson) {
                return makeError(
                    ErrorCode::InvalidFormat,
                    "The GLB file's first chunk is not its JSON chunk (type " + hex(type) + ").");
            }
            chunks.json = data;
            haveJson = true;
        } else if (chunkIndex == 1 && type == kChunkBin) {
            chunks.bin = data;
        }
        // Other chunks are reserved for extensions and skipped, as the specification asks.
        offset = dataOffset + length;
    }
    if (!haveJson) {
        return makeError(ErrorCode::InvalidFormat, "The GLB file has no JSON chunk.");
    }
    return chunks;
}

}  // namespace encore::scene
