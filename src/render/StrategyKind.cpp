#include "encore/render/StrategyKind.h"

#include <algorithm>
#include <array>

namespace encore::render {

namespace {
struct StrategyName {
    StrategyKind kind;
    std::string_view name;
};
constexpr std::array kStrategyNames = {
    StrategyName{StrategyKind::Naive, "naive"},
    StrategyName{StrategyKind::Layouts, "layouts"},
    StrategyName{StrategyKind::PipelineCache, "pipeline-cache"},
    StrategyName{StrategyKind::Instancing, "instancing"},
    StrategyName{StrategyKind::Materials, "materials"},
    StrategyName{StrategyKind::Bundles, "bundles"},
    StrategyName{StrategyKind::GpuCulling, "gpu-culling"},
    StrategyName{StrategyKind::GpuCullingBundles, "gpu-culling-bundles"},
    StrategyName{StrategyKind::Visibility, "visibility"},
};
// The kinds in the order above, so that the names are the one list to extend.
constexpr auto kAllStrategies = [] {
    std::array<StrategyKind, kStrategyNames.size()> kinds{};
    for (std::size_t i = 0; i < kStrategyNames.size(); ++i) {
        kinds[i] = kStrategyNames[i].kind;
    }
    return kinds;
}();
}  // namespace

std::string_view strategyName(StrategyKind kind) {
    for (const auto& entry : kStrategyNames) {
        if (entry.kind == kind) {
            return entry.name;
        }
    }
    return "unknown";
}

std::optional<StrategyKind> strategyFromName(std::string_view name) {
    for (const auto& entry : kStrategyNames) {
        if (entry.name == name) {
            return entry.kind;
        }
    }
    return std::nullopt;
}

std::span<const StrategyKind> allStrategies() {
    return kAllStrategies;
}

std::optional<StrategyKind> bundledKind(StrategyKind kind) {
    switch (kind) {
        case StrategyKind::Materials:
        case StrategyKind::Bundles:
            return StrategyKind::Bundles;
        case StrategyKind::GpuCulling:
        case StrategyKind::GpuCullingBundles:
            return StrategyKind::GpuCullingBundles;
        default:
            return std::nullopt;
    }
}

std::optional<StrategyKind> directKind(StrategyKind kind) {
    switch (kind) {
        case StrategyKind::Bundles:
            return StrategyKind::Materials;
        case StrategyKind::GpuCullingBundles:
            return StrategyKind::GpuCulling;
        default:
            return std::nullopt;
    }
}

bool isBundledKind(StrategyKind kind) {
    return directKind(kind).has_value();
}

bool cullsOnTheGpu(StrategyKind kind) {
    return kind == StrategyKind::GpuCulling || kind == StrategyKind::GpuCullingBundles;
}

StrategyChoice StrategyChoice::of(StrategyKind kind, bool bundle) {
    if (bundle) {
        if (auto bundled = bundledKind(kind)) {
            return {*bundled, false};
        }
    }
    return {kind, bundle};
}

namespace {
constexpr std::string_view kBundleSuffix = "+bundle";
}  // namespace

std::string strategyChoiceName(StrategyChoice choice) {
    const StrategyChoice normal = StrategyChoice::of(choice.kind, choice.bundle);
    std::string name(strategyName(normal.kind));
    if (normal.bundle) {
        name += kBundleSuffix;
    }
    return name;
}

std::optional<StrategyChoice> strategyChoiceFromName(std::string_view name) {
    bool bundle = false;
    if (name.ends_with(kBundleSuffix)) {
        name.remove_suffix(kBundleSuffix.size());
        bundle = true;
    }
    const auto kind = strategyFromName(name);
    if (!kind || (bundle && bundledKind(*kind))) {
        // "bundles+bundle" or "materials+bundle" name no frame of their own: say "bundles".
        return std::nullopt;
    }
    return StrategyChoice{*kind, bundle};
}

std::vector<StrategyChoice> withBundlingAxis(std::span<const StrategyChoice> choices,
                                             bool alsoBundled) {
    std::vector<StrategyChoice> result;
    auto add = [&](StrategyChoice choice) {
        choice = StrategyChoice::of(choice.kind, choice.bundle);
        if (std::find(result.begin(), result.end(), choice) == result.end()) {
            result.push_back(choice);
        }
    };
    for (const auto& choice : choices) {
        add(choice);
        if (alsoBundled) {
            add({choice.kind, true});
        }
    }
    return result;
}

}  // namespace encore::render
