#pragma once

// SVG written as text, for `encore plot`: numbers printed alike whatever the process locale,
// text escaped for XML, and the few elements the plots are made of. Nothing here knows what is
// plotted; colours, dash patterns and marker shapes are the plots' choice.

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace encore::bench {

// `value` in fixed notation with `precision` decimals, "-0.0" printed as "0.0": the same bytes
// on every machine.
std::string svgNumber(double value, int precision = 1);

// `text` with & < > " ' as entities and control characters other than tab as spaces.
std::string escapeXml(std::string_view text);

// A marker's outline around its point, in pixels; an empty outline is a circle.
using Outline = std::vector<std::pair<double, double>>;

// Appends SVG elements to one string; every coordinate goes through svgNumber().
struct SvgBuilder {
    std::string out;

    void text(double x, double y, std::string_view content, std::string_view attributes = {});
    void line(double x1, double y1, double x2, double y2, std::string_view attributes);
    // A marker (class "marker") at (x, y) with `tip` as its tooltip.
    void marker(const Outline& outline, double x, double y, std::string_view tip);
    // Opens a group whose stroke and fill are `colour`; `extra` holds more attributes, each
    // after a space. The caller closes it.
    void beginGroup(std::string_view colour, std::string_view extra = {});
};

}  // namespace encore::bench
