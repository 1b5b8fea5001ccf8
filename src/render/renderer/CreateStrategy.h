#pragma once

// The one place that knows every strategy: the renderer makes its strategy here, by kind.

#include <memory>

#include "encore/render/StrategyKind.h"
#include "render/Strategy.h"

namespace encore::render {

// With `bundle`, the strategy that draws `kind`'s frame from render bundles (see bundledKind).
std::unique_ptr<Strategy> createStrategy(StrategyKind kind, bool bundle = false);

}  // namespace encore::render
