#include "encore/render/Strategy.h"

#include <algorithm>
#include <array>
#include <string>

#include "strategies/BundledStrategy.h"
#include "strategies/BundlesStrategy.h"
#include "strategies/GpuCullingStrategy.h"
#include "strategies/InstancingStrategy.h"
#include "strategies/LayoutsStrategy.h"
#include "strategies/MaterialsStrategy.h"
#include "strategies/NaiveStrategy.h"
#include "strategies/PipelineCacheStrategy.h"

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
};
constexpr std::array kAllStrategies = {StrategyKind::Naive, StrategyKind::Layouts,
                                       StrategyKind::PipelineCache, StrategyKind::Instancing,
                                       StrategyKind::Materials, StrategyKind::Bundles,
                                       StrategyKind::GpuCulling,
                                       StrategyKind::GpuCullingBundles};
}  // namespace

PrepareTimes& PrepareTimes::operator+=(const PrepareTimes& other) {
    release += other.release;
    animation += other.animation;
    strategy += other.strategy;
    geometry += other.geometry;
    instances += other.instances;
    materials += other.materials;
    textureCreation += other.textureCreation;
    textureWrites += other.textureWrites;
    mipmaps += other.mipmaps;
    materialSubmit += other.materialSubmit;
    draws += other.draws;
    checks += other.checks;
    return *this;
}

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

Result<void> checkInstanceIndex(std::size_t instance, std::size_t instanceCount) {
    if (instance >= instanceCount) {
        return makeError(ErrorCode::InvalidArgument,
                         "Instance " + std::to_string(instance) + " does not exist (the scene has " +
                             std::to_string(instanceCount) + " instances).");
    }
    return {};
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

std::unique_ptr<Strategy> createStrategy(StrategyKind kind, bool bundle) {
    if (bundle) {
        if (auto bundled = bundledKind(kind)) {
            return createStrategy(*bundled);
        }
        return std::make_unique<BundledStrategy>(createStrategy(kind));
    }
    switch (kind) {
        case StrategyKind::Naive:
            return std::make_unique<NaiveStrategy>();
        case StrategyKind::Layouts:
            return std::make_unique<LayoutsStrategy>();
        case StrategyKind::PipelineCache:
            return std::make_unique<PipelineCacheStrategy>();
        case StrategyKind::Instancing:
            return std::make_unique<InstancingStrategy>();
        case StrategyKind::Materials:
            return std::make_unique<MaterialsStrategy>();
        case StrategyKind::Bundles:
            return std::make_unique<BundlesStrategy>();
        case StrategyKind::GpuCulling:
            return std::make_unique<GpuCullingStrategy>(false);
        case StrategyKind::GpuCullingBundles:
            return std::make_unique<GpuCullingStrategy>(true);
    }
    return nullptr;
}

}  // namespace encore::render
