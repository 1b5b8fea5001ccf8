// glTF uris: data: uris (base64 or percent-encoded) and relative references, percent-decoded and
// resolved against the directory of the .gltf file. Buffers are loaded here too, since a buffer
// is nothing but the bytes behind its uri (or the GLB BIN chunk).

#include <array>
#include <filesystem>
#include <iterator>

#include "core/FileIO.h"
#include "scene/LoadContext.h"

namespace encore::scene {
namespace {

int hexValue(char c) {
    if (c >= '0' && c <= '9') {
        return c - '0';
    }
    if (c >= 'a' && c <= 'f') {
        return c - 'a' + 10;
    }
    if (c >= 'A' && c <= 'F') {
        return c - 'A' + 10;
    }
    return -1;
}

constexpr std::array<std::int8_t, 256> makeBase64Table() {
    std::array<std::int8_t, 256> table{};
    for (auto& entry : table) {
        entry = -1;
    }
    constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (int i = 0; i < 64; ++i) {
        table[static_cast<unsigned char>(kAlphabet[i])] = std::int8_t(i);
    }
    // The URL-safe alphabet too: some exporters write it.
    table[static_cast<unsigned char>('-')] = 62;
    table[static_cast<unsigned char>('_')] = 63;
    return table;
}

Result<std::vector<std::uint8_t>> decodeBase64(std::string_view text) {
    static constexpr auto kTable = makeBase64Table();
    std::vector<std::uint8_t> bytes;
    bytes.reserve(text.size() / 4 * 3);
    std::uint32_t accumulator = 0;
    int bits = 0;
    std::size_t position = 0;
    for (; position < text.size(); ++position) {
        const char c = text[position];
        if (c == '=') {
            break;
        }
        if (c == '\n' || c == '\r' || c == ' ') {
            continue;
        }
        const int value = kTable[static_cast<unsigned char>(c)];
        if (value < 0) {
            return makeError(ErrorCode::InvalidFormat,
                             "The data: uri holds a character that is not base64 (at position " +
                                 std::to_string(position) + ").");
        }
        accumulator = (accumulator << 6) | std::uint32_t(value);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            bytes.push_back(std::uint8_t((accumulator >> bits) & 0xFF));
        }
    }
    for (; position < text.size(); ++position) {
        if (text[position] != '=') {
            return makeError(ErrorCode::InvalidFormat,
                             "The data: uri has base64 data after its padding (at position " +
                                 std::to_string(position) + ").");
        }
    }
    return bytes;
}

std::string shortUri(std::string_view uri) {
    constexpr std::size_t kMaxLength = 60;
    return uri.size() <= kMaxLength ? std::string(uri)
                                    : std::string(uri.substr(0, kMaxLength - 3)) + "...";
}

}  // namespace

std::string percentDecode(std::string_view text) {
    std::string result;
    result.reserve(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '%' && i + 2 < text.size() && hexValue(text[i + 1]) >= 0 &&
            hexValue(text[i + 2]) >= 0) {
            result.push_back(char(hexValue(text[i + 1]) * 16 + hexValue(text[i + 2])));
            i += 2;
        } else {
            result.push_back(text[i]);
        }
    }
    return result;
}

bool isDataUri(std::string_view uri) {
    return uri.substr(0, 5) == "data:";
}

Result<std::vector<std::uint8_t>> decodeDataUri(std::string_view uri) {
    const std::size_t comma = uri.find(',');
    if (!isDataUri(uri) || comma == std::string_view::npos) {
        return makeError(ErrorCode::InvalidFormat,
                         "The data: uri '" + shortUri(uri) + "' has no ',' before its data.");
    }
    const std::string_view header = uri.substr(5, comma - 5);
    const std::string_view payload = uri.substr(comma + 1);
    if (header.size() >= 7 && header.substr(header.size() - 7) == ";base64") {
        return decodeBase64(payload);
    }
    const std::string decoded = percentDecode(payload);
    return std::vector<std::uint8_t>(decoded.begin(), decoded.end());
}

namespace {

// Whether `path` is `folder` or lies under it, both absolute and normal.
bool isWithin(const std::filesystem::path& path, const std::filesystem::path& folder) {
    auto inner = path.begin();
    for (auto outer = folder.begin(); outer != folder.end(); ++outer, ++inner) {
        if (outer->empty() && std::next(outer) == folder.end()) {
            break;  // The empty last element of a folder written with a trailing '/'.
        }
        if (inner == path.end() || *inner != *outer) {
            return false;
        }
    }
    return true;
}

// `decoded` (relative to the scope's folder) with every link of its existing part followed, or
// an error when it leads out of the folder.
Result<void> checkInside(const std::string& uri,
                         const std::filesystem::path& decoded,
                         const UriScope& scope) {
    namespace fs = std::filesystem;
    const auto outside = [&](const fs::path& folder) {
        return makeError(ErrorCode::FileUnreadable,
                         "\"" + shortUri(uri) + "\" is outside the model's folder ('" +
                             folder.string() +
                             "'); only files inside it are read (--allow-uris-outside reads "
                             "others).");
    };
    std::error_code ec;
    const fs::path folder =
        fs::weakly_canonical(scope.folder.empty() ? fs::path(".") : scope.folder, ec);
    if (ec) {
        return makeError(ErrorCode::FileUnreadable, "The model's folder '" + scope.folder.string() +
                                                        "' cannot be resolved (" + ec.message() +
                                                        ").");
    }
    if (decoded.has_root_path()) {
        return outside(folder);
    }
    // Links are followed as far as the path exists, `..` resolved after them (a link to a
    // folder outside, then `..`, stays outside).
    const fs::path resolved = fs::weakly_canonical(folder / decoded, ec);
    if (ec || !isWithin(resolved, folder)) {
        return outside(folder);
    }
    return {};
}

}  // namespace

Result<std::filesystem::path> resolveUriPath(std::string_view uri, const UriScope& scope) {
    const std::size_t colon = uri.find(':');
    const std::size_t slash = uri.find('/');
    // "scheme:" before any '/' is a uri scheme (http:, file:), not a relative path.
    if (colon != std::string_view::npos && colon > 1 &&
        (slash == std::string_view::npos || colon < slash)) {
        return makeError(ErrorCode::Unsupported, "The uri '" + shortUri(uri) +
                                                     "' is not a relative file reference or a "
                                                     "data: uri.");
    }
    std::string decoded = percentDecode(uri);
    // A query or fragment never names part of a local file.
    if (const auto query = decoded.find_first_of("?#"); query != std::string::npos) {
        decoded.resize(query);
    }
    const std::filesystem::path relative(decoded);
    if (!scope.allowOutside) {
        ENCORE_TRY(checkInside(decoded, relative, scope));
    }
    return scope.folder / relative;
}

Result<std::vector<std::uint8_t>> readUri(std::string_view uri, const UriScope& scope) {
    if (isDataUri(uri)) {
        return decodeDataUri(uri);
    }
    std::filesystem::path path;
    ENCORE_TRY_ASSIGN(path, resolveUriPath(uri, scope));
    return readFile(path);
}

Result<void> loadBuffers(LoadContext& context) {
    const auto& buffers = context.document.buffers;
    context.scene.buffers.resize(buffers.size());
    for (std::size_t i = 0; i < buffers.size(); ++i) {
        const GltfBuffer& source = buffers[i];
        Buffer& buffer = context.scene.buffers[i];
        const std::string element = "buffer " + std::to_string(i);
        if (!source.uri) {
            if (i == 0 && context.glbBinChunk) {
                buffer.name = "GLB BIN chunk";
                buffer.bytes.assign(context.glbBinChunk->begin(), context.glbBinChunk->end());
            } else if (source.meshoptFallback) {
                // Only compressed views point here; they are decoded from other buffers.
                buffer.name = "EXT_meshopt_compression fallback";
                continue;
            } else {
                return makeError(ErrorCode::InvalidFormat,
                                 element + " has no uri and is not the GLB BIN chunk.");
            }
        } else {
            buffer.name = isDataUri(*source.uri) ? "data: uri of " + element : *source.uri;
            auto bytes = readUri(*source.uri, context.uriScope());
            if (!bytes.ok()) {
                if (source.meshoptFallback) {
                    continue;  // A fallback need not exist when the decoder is present.
                }
                return bytes.error().withContext(element + " ('" + shortUri(*source.uri) +
                                                 "') cannot be loaded");
            }
            buffer.bytes = std::move(bytes).value();
        }
        if (buffer.bytes.size() < source.byteLength) {
            return makeError(ErrorCode::InvalidFormat,
                             element + " is shorter than its byteLength (" +
                                 std::to_string(buffer.bytes.size()) + " bytes < " +
                                 std::to_string(source.byteLength) + ").");
        }
        // GLB pads the BIN chunk; views are checked against the declared length.
        buffer.bytes.resize(static_cast<std::size_t>(source.byteLength));
    }
    return {};
}

}  // namespace encore::scene
