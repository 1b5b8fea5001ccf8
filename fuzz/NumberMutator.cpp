// The structure-aware mutation of encore_fuzz_numbers (FuzzNumbers.cpp), free of libFuzzer so
// that the frame fuzzer (FrameFuzzer.cpp, built by g++ with the GPU libraries) mutates its inputs
// with the very same code. See NumberMutator.h for what it changes.

#include "NumberMutator.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <string>
#include <string_view>
#include <vector>

namespace encore::fuzz {
namespace {

using Json = nlohmann::json;
using Random = std::mt19937;

// A glTF document: its JSON and, for a GLB, the chunks that follow the JSON chunk, verbatim.
struct Document {
    Json json;
    bool binary = false;
    std::uint32_t version = 2;
    std::string trailing;  // bytes after the JSON chunk (the BIN chunk with its header)
};

std::uint32_t readU32(const std::uint8_t* bytes) {
    return std::uint32_t(bytes[0]) | std::uint32_t(bytes[1]) << 8 | std::uint32_t(bytes[2]) << 16 |
           std::uint32_t(bytes[3]) << 24;
}

void writeU32(std::string& out, std::size_t at, std::uint32_t value) {
    for (int i = 0; i < 4; ++i) {
        out[at + i] = char((value >> (8 * i)) & 0xFF);
    }
}

std::optional<Document> parseDocument(const std::uint8_t* data, std::size_t size) {
    Document document;
    std::string_view text(reinterpret_cast<const char*>(data), size);
    if (size >= 4 && std::memcmp(data, "glTF", 4) == 0) {
        if (size < 20) {
            return std::nullopt;
        }
        document.binary = true;
        document.version = readU32(data + 4);
        const std::uint64_t jsonLength = readU32(data + 12);
        if (std::memcmp(data + 16, "JSON", 4) != 0 || jsonLength > size - 20) {
            return std::nullopt;
        }
        text = text.substr(20, jsonLength);
        document.trailing.assign(reinterpret_cast<const char*>(data) + 20 + jsonLength,
                                 size - 20 - jsonLength);
    }
    document.json = Json::parse(text.begin(), text.end(), nullptr, false);
    if (document.json.is_discarded() || !document.json.is_object()) {
        return std::nullopt;
    }
    return document;
}

// Properties whose numbers the loader checks or trusts: sizes, offsets, enums and the indices
// of other objects. Elements of arrays under these keys count too (min, max, children, ...).
bool mattersKey(std::string_view key) {
    static constexpr std::string_view keys[] = {"count",         "byteOffset",
                                                "componentType", "byteLength",
                                                "byteStride",    "bufferView",
                                                "buffer",        "min",
                                                "max",           "indices",
                                                "material",      "mesh",
                                                "node",          "nodes",
                                                "children",      "skin",
                                                "joints",        "skeleton",
                                                "camera",        "sampler",
                                                "source",        "index",
                                                "texCoord",      "input",
                                                "output",        "inverseBindMatrices",
                                                "scene",         "scenes",
                                                "mode",          "target",
                                                "light",         "magFilter",
                                                "minFilter",     "wrapS",
                                                "wrapT",         "width",
                                                "height",        "weights",
                                                "channels",      "samplers"};
    return std::find(std::begin(keys), std::end(keys), key) != std::end(keys);
}

struct Site {
    Json* value;
    std::string key;  // the object key at or above the number ("count", "POSITION", ...)
};

// Every number of the document; those at keys that matter first (`important` of them).
void collectNumbers(Json& json,
                    const std::string& key,
                    bool underAttributes,
                    std::vector<Site>& important,
                    std::vector<Site>& others) {
    if (json.is_number()) {
        (underAttributes || mattersKey(key) ? important : others).push_back({&json, key});
    } else if (json.is_object()) {
        for (auto& [name, child] : json.items()) {
            collectNumbers(child, name,
                           underAttributes || name == "attributes" || name == "targets", important,
                           others);
        }
    } else if (json.is_array()) {
        for (auto& child : json) {
            collectNumbers(child, key, underAttributes, important, others);
        }
    }
}

// Literal texts nlohmann never writes; stored as marked strings and substituted after dump().
constexpr std::string_view kLiteralMark = "\x01literal:";
// NaN and Infinity are not JSON (the loader must refuse them); the others are.
constexpr std::string_view kLiterals[] = {"NaN", "Infinity", "1e999",        "-1e999",
                                          "-0",  "1e-400",   "4294967296.0", "1e308"};

double asDouble(const Json& value) {
    return value.is_number() ? value.get<double>() : 0.0;
}

// The integer part of a number, or 0 past 2^62: twice it, or it plus a few, must still fit in
// an int64_t (a signed overflow here is undefined behaviour, which UBSan stops the fuzzer on).
std::int64_t integerPart(double value) {
    constexpr double kLimit = 4611686018427387904.0;  // 2^62
    return std::isfinite(value) && std::fabs(value) < kLimit ? std::int64_t(value) : 0;
}

Json boundaryValue(const Json& original, const std::vector<Site>& all, Random& random) {
    const double v = asDouble(original);
    const std::int64_t i = integerPart(v);
    auto pick = [&](std::size_t n) { return std::size_t(random() % n); };
    switch (pick(24)) {
        case 0:
            return 0;
        case 1:
            return 1;
        case 2:
            return -1;
        case 3:
            return i + 1;
        case 4:
            return i - 1;
        case 5:
            return i * 2;
        case 6:
            return i / 2;
        case 7:
            return std::int64_t(std::numeric_limits<std::int32_t>::max());
        case 8:
            return std::uint64_t(std::numeric_limits<std::uint32_t>::max());
        case 9:
            return std::uint64_t(1) << 32;
        case 10:
            return std::uint64_t(1) << 31;
        case 11:
            return std::uint64_t(1) << 63;
        case 12:
            return std::numeric_limits<std::uint64_t>::max();
        case 13:
            return std::int64_t(std::numeric_limits<std::int32_t>::min());
        case 14:
            return 1e300;
        case 15:
            return -1e300;
        case 16:
            return std::numeric_limits<double>::quiet_NaN();  // dumped as null
        case 17:
            return v + 0.5;
        case 18:
            return std::string(kLiteralMark) + std::string(kLiterals[pick(std::size(kLiterals))]);
        case 19: {
            // A component type or the glTF enum nearest to it.
            static constexpr std::int64_t enums[] = {5120, 5121, 5122, 5123, 5124,  5125,  5126,
                                                     5119, 5127, 9728, 9729, 33071, 33648, 10497};
            return enums[pick(std::size(enums))];
        }
        case 20:
            return std::int64_t(1) << pick(40);
        case 21:
            return i + std::int64_t(pick(9)) - 4;
        default: {
            // Another number of the document, as is or a little off: the count of another
            // accessor, the length of a view, a buffer's size.
            const std::int64_t j = integerPart(asDouble(*all[pick(all.size())].value));
            static constexpr std::int64_t deltas[] = {0, 1, -1, 4, -4};
            return j + deltas[pick(std::size(deltas))];
        }
    }
}

std::string dumpJson(const Json& json) {
    std::string text = json.dump(-1, ' ', false, Json::error_handler_t::replace);
    // "\u0001literal:NaN" (as dump() escapes the mark) -> NaN
    const std::string mark = "\"\\u0001literal:";
    for (std::size_t at = text.find(mark); at != std::string::npos; at = text.find(mark, at)) {
        const std::size_t end = text.find('"', at + mark.size());
        if (end == std::string::npos) {
            break;
        }
        text.replace(at, end + 1 - at, text.substr(at + mark.size(), end - at - mark.size()));
    }
    return text;
}

// JSON text or GLB bytes; a GLB's lengths are right unless `breakLengths`.
std::string serialise(const Document& document, Random& random, bool breakLengths) {
    std::string text = dumpJson(document.json);
    if (!document.binary) {
        return text;
    }
    while (text.size() % 4 != 0) {
        text.push_back(' ');
    }
    std::string out(20, '\0');
    std::memcpy(out.data(), "glTF", 4);
    std::memcpy(out.data() + 16, "JSON", 4);
    out += text;
    out += document.trailing;
    writeU32(out, 4, document.version);
    writeU32(out, 8, std::uint32_t(out.size()));
    writeU32(out, 12, std::uint32_t(text.size()));
    if (breakLengths) {
        static constexpr std::int64_t deltas[] = {-8, -4, -1, 1, 4, 8};
        const std::size_t binHeader = 20 + text.size();
        const bool hasBin = document.trailing.size() >= 8;
        switch (random() % (hasBin ? 4 : 2)) {
            case 0: {  // header length
                const auto value = std::int64_t(out.size()) + deltas[random() % std::size(deltas)];
                writeU32(out, 8, random() % 4 == 0 ? 0xFFFFFFFFu : std::uint32_t(value));
                break;
            }
            case 1: {  // JSON chunk length
                const auto value = std::int64_t(text.size()) + deltas[random() % std::size(deltas)];
                writeU32(out, 12, random() % 4 == 0 ? 0xFFFFFFFFu : std::uint32_t(value));
                break;
            }
            default: {  // BIN chunk length
                const std::uint32_t length =
                    readU32(reinterpret_cast<const std::uint8_t*>(out.data() + binHeader));
                const auto value = std::int64_t(length) + deltas[random() % std::size(deltas)];
                writeU32(out, binHeader, random() % 4 == 0 ? 0xFFFFFFFFu : std::uint32_t(value));
                break;
            }
        }
    }
    return out;
}

std::size_t writeOut(const std::string& bytes, std::uint8_t* data, std::size_t maxSize) {
    if (bytes.size() > maxSize) {
        return 0;
    }
    std::memcpy(data, bytes.data(), bytes.size());
    return bytes.size();
}

}  // namespace

std::size_t mutateNumbers(std::uint8_t* data,
                          std::size_t size,
                          std::size_t maxSize,
                          unsigned seed) {
    Random random(seed);
    // Now and then a byte-level mutation, for what numbers alone cannot reach.
    if (random() % 16 == 0) {
        return 0;
    }
    auto document = parseDocument(data, size);
    if (!document) {
        return 0;
    }
    std::vector<Site> important;
    std::vector<Site> others;
    collectNumbers(document->json, "", false, important, others);
    if (important.empty() && others.empty()) {
        return 0;
    }
    std::vector<Site> all = important;
    all.insert(all.end(), others.begin(), others.end());
    const unsigned changes = 1 + (random() % 4 == 0 ? random() % 3 : 0);
    std::vector<Json> values;
    std::vector<Json*> targets;
    for (unsigned c = 0; c < changes; ++c) {
        const auto& pool =
            important.empty() || (!others.empty() && random() % 8 == 0) ? others : important;
        Json* target = pool[random() % pool.size()].value;
        // Decide every new value before writing any, so `all` still holds numbers.
        values.push_back(boundaryValue(*target, all, random));
        targets.push_back(target);
    }
    for (std::size_t c = 0; c < targets.size(); ++c) {
        *targets[c] = values[c];
    }
    const bool breakLengths = document->binary && random() % 8 == 0;
    return writeOut(serialise(*document, random, breakLengths), data, maxSize);
}

std::size_t crossOverNumbers(const std::uint8_t* data1,
                             std::size_t size1,
                             const std::uint8_t* data2,
                             std::size_t size2,
                             std::uint8_t* out,
                             std::size_t maxOutSize,
                             unsigned seed) {
    Random random(seed);
    auto first = parseDocument(data1, size1);
    auto second = parseDocument(data2, size2);
    if (!first || !second) {
        return 0;
    }
    std::vector<Site> mine, mineOthers, theirs, theirsOthers;
    collectNumbers(first->json, "", false, mine, mineOthers);
    collectNumbers(second->json, "", false, theirs, theirsOthers);
    if (mine.empty() || theirs.empty()) {
        return 0;
    }
    // A number of the second document replaces a number at the same key in the first (the
    // count of one model's accessor in another's).
    for (unsigned attempt = 0, done = 0; attempt < 16 && done < 2; ++attempt) {
        Site& target = mine[random() % mine.size()];
        const Site& source = theirs[random() % theirs.size()];
        if (target.key == source.key) {
            *target.value = *source.value;
            ++done;
        }
    }
    return writeOut(serialise(*first, random, false), out, maxOutSize);
}

}  // namespace encore::fuzz
