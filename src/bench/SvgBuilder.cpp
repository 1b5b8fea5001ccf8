#include "bench/SvgBuilder.h"

#include <array>
#include <charconv>

namespace encore::bench {

// Fixed notation through to_chars, because printf-style formatting follows the process locale
// and a decimal comma would corrupt the SVG.
std::string svgNumber(double value, int precision) {
    std::array<char, 64> buffer{};
    auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value,
                                   std::chars_format::fixed, precision);
    std::string text(buffer.data(), ec == std::errc() ? end : buffer.data());
    // -0.0 and 0.0 are the same coordinate; print them alike so output stays byte-stable.
    if (text[0] == '-' && text.find_first_not_of("-0.") == std::string::npos) {
        text.erase(0, 1);
    }
    return text;
}

std::string escapeXml(std::string_view text) {
    constexpr std::string_view kSpecial = "&<>\"'";
    constexpr std::array<std::string_view, 5> kEntities = {"&amp;", "&lt;", "&gt;", "&quot;",
                                                           "&apos;"};
    std::string out;
    for (char c : text) {
        if (size_t i = kSpecial.find(c); i != std::string_view::npos) {
            out += kEntities[i];
        } else {
            // XML 1.0 forbids most control characters, even as character references.
            out += (static_cast<unsigned char>(c) < 0x20 && c != '\t') ? ' ' : c;
        }
    }
    return out;
}

void SvgBuilder::text(double x, double y, std::string_view content, std::string_view attributes) {
    out += "<text x=\"" + svgNumber(x) + "\" y=\"" + svgNumber(y) + "\" " +
           std::string(attributes) + ">" + escapeXml(content) + "</text>\n";
}

void SvgBuilder::line(double x1, double y1, double x2, double y2, std::string_view attributes) {
    out += "<line x1=\"" + svgNumber(x1) + "\" y1=\"" + svgNumber(y1) + "\" x2=\"" + svgNumber(x2) +
           "\" y2=\"" + svgNumber(y2) + "\" " + std::string(attributes) + "/>\n";
}

void SvgBuilder::marker(const Outline& outline, double x, double y, std::string_view tip) {
    const std::string tag = outline.empty() ? "circle" : "polygon";
    out += "<" + tag + " class=\"marker\"";
    if (outline.empty()) {
        out += " cx=\"" + svgNumber(x) + "\" cy=\"" + svgNumber(y) + "\" r=\"3.5\"";
    } else {
        out += " points=\"";
        for (size_t i = 0; i < outline.size(); ++i) {
            out += (i ? " " : "") + svgNumber(x + outline[i].first) + "," +
                   svgNumber(y + outline[i].second);
        }
        out += "\"";
    }
    // A <title> child is the tooltip browsers show on hover: the numbers behind a point.
    out += "><title>" + escapeXml(tip) + "</title></" + tag + ">\n";
}

void SvgBuilder::beginGroup(std::string_view colour, std::string_view extra) {
    const std::string paint(colour);
    out += "<g" + std::string(extra) + " stroke=\"" + paint + "\" fill=\"" + paint + "\">\n";
}

}  // namespace encore::bench
