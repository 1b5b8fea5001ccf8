#include "encore/render/RendererStats.h"

#include <algorithm>
#include <cmath>

namespace encore::render {

Percentiles Percentiles::of(std::vector<double> values) {
    Percentiles result;
    if (values.empty()) {
        return result;
    }
    std::sort(values.begin(), values.end());
    auto at = [&](double fraction) {
        // Nearest rank: the smallest value with at least `fraction` of the values at or below.
        const auto rank = static_cast<std::size_t>(std::ceil(fraction * double(values.size())));
        return values[std::clamp<std::size_t>(rank, 1, values.size()) - 1];
    };
    result.median = values.size() % 2 == 1
                        ? values[values.size() / 2]
                        : 0.5 * (values[values.size() / 2 - 1] + values[values.size() / 2]);
    result.p95 = at(0.95);
    return result;
}

}  // namespace encore::render
