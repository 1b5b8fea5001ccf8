#include "StrategyOptions.h"

namespace encore::app {

namespace {

std::string knownNames() {
    std::string names;
    for (auto kind : render::allStrategies()) {
        names += (names.empty() ? "" : ", ") + std::string(render::strategyName(kind));
    }
    return names + ", or a direct one with +bundle (naive+bundle)";
}

}  // namespace

Result<render::StrategyChoice> parseStrategyChoice(const std::string& name, bool bundle) {
    const auto choice = render::strategyChoiceFromName(name);
    if (!choice) {
        return makeError(ErrorCode::InvalidArgument,
                         "Unknown strategy '" + name + "' (known: " + knownNames() + ").");
    }
    return render::StrategyChoice::of(choice->kind, choice->bundle || bundle);
}

Result<std::vector<render::StrategyChoice>> parseStrategySelection(
    const std::vector<std::string>& names,
    bool alsoBundled) {
    std::vector<render::StrategyChoice> choices;
    if (names.empty()) {
        for (auto kind : render::allStrategies()) {
            choices.push_back({kind, false});
        }
    }
    for (const auto& name : names) {
        ENCORE_TRY_ASSIGN(auto choice, parseStrategyChoice(name, false));
        choices.push_back(choice);
    }
    return render::withBundlingAxis(choices, alsoBundled);
}

}  // namespace encore::app
