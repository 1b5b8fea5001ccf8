#pragma once

// Strategy names on the command line, shared by render, stats, bench and view: a kind's name, or
// "<name>+bundle" for a kind recorded once into render bundles by the bundling wrapper.

#include <string>
#include <vector>

#include "encore/core/Result.h"
#include "encore/render/StrategyKind.h"

namespace encore::app {

// `name` (e.g. "naive", "bundles", "naive+bundle"), bundled when `bundle` is set.
Result<render::StrategyChoice> parseStrategyChoice(const std::string& name, bool bundle);

// `names` (every strategy when empty), each followed by its bundled form when `alsoBundled`.
Result<std::vector<render::StrategyChoice>> parseStrategySelection(
    const std::vector<std::string>& names,
    bool alsoBundled);

}  // namespace encore::app
