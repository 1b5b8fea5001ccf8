#include "ByteSize.h"

#include <cctype>
#include <cmath>
#include <cstdlib>

namespace encore::app {

Result<std::uint64_t> parseByteSize(const std::string& text, const std::string& option) {
    char* end = nullptr;
    const double number = std::strtod(text.c_str(), &end);
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
    if (end == text.c_str() || !unitValid || !std::isfinite(number) || unit.size() > 1 ||
        number * scale < 1.0 || number * scale > 1e18) {
        return makeError(
            ErrorCode::InvalidArgument,
            option + " takes a size in bytes, such as 1GiB, 500MB or 1000000 ('" + text + "').");
    }
    return std::uint64_t(number * scale);
}

}  // namespace encore::app
