#include "batch/OptionValues.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "image/Srgb.h"

namespace encore::batch {

namespace {

Error invalid(std::string_view shown, const std::string& takes, std::string_view text) {
    return makeError(ErrorCode::InvalidArgument, std::string(shown) + " takes " + takes +
                                                     " (not '" + std::string(text) + "').");
}

// The whole text as a finite float.
bool finiteNumber(std::string_view text, float& value) {
    const std::string copy(text);  // strtof needs a terminated string.
    char* end = nullptr;
    value = std::strtof(copy.c_str(), &end);
    return !copy.empty() && end == copy.c_str() + copy.size() && std::isfinite(value);
}

}  // namespace

Result<bool> parseFlag(std::string_view text, std::string_view shown) {
    if (text == "true") {
        return true;
    }
    if (text == "false") {
        return false;
    }
    return invalid(shown, "true or false", text);
}

Result<std::uint64_t> parseWholeNumber(std::string_view text,
                                       std::string_view shown,
                                       std::uint64_t min,
                                       std::uint64_t max) {
    std::uint64_t value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || error != std::errc() || end != text.data() + text.size() || value < min ||
        value > max) {
        return invalid(shown,
                       "a whole number from " + std::to_string(min) + " to " + std::to_string(max),
                       text);
    }
    return value;
}

Result<float> parseNumber(std::string_view text, std::string_view shown, float min, float max) {
    float value = 0.0f;
    if (!finiteNumber(text, value) || value < min || value > max) {
        const auto bound = [](float limit) {
            std::string written = std::to_string(limit);
            written.erase(written.find_last_not_of('0') + 1);
            if (written.ends_with('.')) {
                written.pop_back();
            }
            return written;
        };
        const bool unbounded = max >= 3.0e38f;
        return invalid(shown,
                       unbounded ? "a number of at least " + bound(min)
                                 : "a number from " + bound(min) + " to " + bound(max),
                       text);
    }
    return value;
}

Result<ValueRange> parseRange(std::string_view text, std::string_view shown) {
    const std::size_t colon = text.find(':');
    ValueRange range;
    const bool parsed = colon == std::string_view::npos
                            ? finiteNumber(text, range.min) && finiteNumber(text, range.max)
                            : finiteNumber(text.substr(0, colon), range.min) &&
                                  finiteNumber(text.substr(colon + 1), range.max);
    if (!parsed) {
        return invalid(shown, "a number or a range MIN:MAX", text);
    }
    return range;
}

Result<std::vector<float>> parseNumberList(std::string_view text,
                                           std::string_view shown,
                                           std::size_t maxCount) {
    std::vector<float> values;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = text.find(',', start);
        const std::string_view item = text.substr(
            start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
        float value = 0.0f;
        if (!finiteNumber(item, value)) {
            return invalid(shown,
                           "numbers separated by commas, A,B,... ('" + std::string(item) +
                               "' is not a number)",
                           text);
        }
        values.push_back(value);
        if (values.size() > maxCount) {
            return invalid(shown, "at most " + std::to_string(maxCount) + " numbers", text);
        }
        if (comma == std::string_view::npos) {
            return values;
        }
        start = comma + 1;
    }
}

Result<std::pair<std::uint32_t, std::uint32_t>> parseImageSize(std::string_view text,
                                                               std::string_view shown) {
    const std::size_t x = text.find('x');
    const auto side = [](std::string_view part) -> long {
        std::uint32_t value = 0;
        const auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), value);
        return part.empty() || part.size() > 5 || error != std::errc() ||
                       end != part.data() + part.size()
                   ? -1
                   : long(value);
    };
    const long width = side(text.substr(0, x));
    const long height = x == std::string_view::npos ? width : side(text.substr(x + 1));
    if (width < 1 || height < 1 || width > 8192 || height > 8192) {
        return invalid(shown, "W or WxH in pixels, each from 1 to 8192", text);
    }
    return std::pair{std::uint32_t(width), std::uint32_t(height)};
}

Result<std::uint64_t> parseByteSize(std::string_view text, std::string_view shown) {
    const std::string copy(text);
    char* end = nullptr;
    const double number = std::strtod(copy.c_str(), &end);
    std::string unit(end);
    for (char& c : unit) {
        c = char(std::tolower(static_cast<unsigned char>(c)));
    }
    if (unit.ends_with('b')) {
        unit.pop_back();
    }
    const bool binary = unit.ends_with('i');
    if (binary) {
        unit.pop_back();
    }
    const std::size_t prefix = unit.size() == 1 ? std::string("kmgt").find(unit[0]) : 0;
    const bool unitValid = unit.size() == 1 ? prefix != std::string::npos : !binary;
    const double scale =
        unit.empty() ? 1.0 : std::pow(binary ? 1024.0 : 1000.0, double(prefix + 1));
    if (end == copy.c_str() || !unitValid || !std::isfinite(number) || unit.size() > 1 ||
        number * scale < 1.0 || number * scale > 1e18) {
        return invalid(shown, "a size in bytes, such as 1GiB, 500MB or 1000000", text);
    }
    return std::uint64_t(number * scale);
}

Result<void> parseBackground(std::string_view text,
                             std::string_view shown,
                             render::ToneMappingOptions& options) {
    if (text == "transparent") {
        options.background = render::BackgroundKind::Transparent;
        return {};
    }
    if (text == "env") {
        options.background = render::BackgroundKind::Environment;
        return {};
    }
    glm::vec3 color;
    const bool hex = text.size() == 7 && text[0] == '#' &&
                     text.find_first_not_of("0123456789abcdefABCDEF", 1) == std::string_view::npos;
    for (int channel = 0; hex && channel < 3; ++channel) {
        unsigned value = 0;
        const char* digits = text.data() + 1 + 2 * channel;
        std::from_chars(digits, digits + 2, value, 16);
        color[channel] = float(image::srgbToLinear(value / 255.0));
    }
    if (!hex) {
        return invalid(shown, "transparent, env or a colour written #rrggbb", text);
    }
    options.background = render::BackgroundKind::Color;
    options.backgroundColor = color;
    return {};
}

std::string nearestName(std::string_view name, const std::vector<std::string>& names) {
    // Levenshtein distance, one row at a time.
    const auto distance = [](std::string_view a, std::string_view b) {
        std::vector<std::size_t> row(b.size() + 1);
        for (std::size_t j = 0; j <= b.size(); ++j) {
            row[j] = j;
        }
        for (std::size_t i = 1; i <= a.size(); ++i) {
            std::size_t diagonal = row[0];
            row[0] = i;
            for (std::size_t j = 1; j <= b.size(); ++j) {
                const std::size_t above = row[j];
                row[j] = std::min(
                    {row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
                diagonal = above;
            }
        }
        return row[b.size()];
    };
    std::string best;
    std::size_t bestDistance = std::max<std::size_t>(2, name.size() / 3) + 1;
    for (const std::string& candidate : names) {
        const std::size_t d = distance(name, candidate);
        if (d < bestDistance) {
            best = candidate;
            bestDistance = d;
        }
    }
    return best;
}

}  // namespace encore::batch
