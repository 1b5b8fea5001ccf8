// encore info [MODEL] [--json]: without a model, every GPU adapter and the one Encore uses; with
// one, what the loader made of it (ModelInfo.h). The model summary never creates a GPU device, so
// it works on machines without a Vulkan adapter.

#include <cstdio>
#include <memory>
#include <string>

#include "Commands.h"
#include "encore/gpu/Context.h"
#include "scene/ModelInfo.h"

namespace encore::app {
namespace {

struct InfoOptions {
    std::string model;
    bool json = false;
};

// Every adapter, the one the options choose marked; the chosen one is also created, so a
// device that cannot be made fails here rather than in the first render.
int printAdapters(const GlobalOptions& global, bool json) {
    auto adapters = gpu::listAdapters(global.allowNullBackend);
    if (!adapters) {
        return reportError(adapters.error());
    }
    auto context = createContext(global);
    if (!context) {
        return reportError(context.error());
    }
    const auto& chosen = context->adapterDescription();
    if (json) {
        nlohmann::json list = nlohmann::json::array();
        for (const gpu::AdapterDescription& adapter : *adapters) {
            list.push_back({{"index", adapter.index},
                            {"name", adapter.name},
                            {"backend", gpu::backendName(adapter.backend)},
                            {"type", gpu::adapterTypeName(adapter.adapterType)},
                            {"driver", adapter.driver},
                            {"vendor", adapter.vendor},
                            {"architecture", adapter.architecture}});
        }
        const nlohmann::json report = {{"adapter", chosen.summary()},
                                       {"device", chosen.index},
                                       {"vendor", chosen.vendor},
                                       {"architecture", chosen.architecture},
                                       {"adapters", list}};
        std::printf("%s\n", report.dump(2).c_str());
    } else {
        std::printf("adapter: %s\n", chosen.summary().c_str());
        std::printf("vendor: %s\narchitecture: %s\n", chosen.vendor.c_str(),
                    chosen.architecture.c_str());
        std::printf("adapters (--device N):\n");
        for (const gpu::AdapterDescription& adapter : *adapters) {
            std::printf("%s %zu: %s\n", adapter.index == chosen.index ? "*" : " ", adapter.index,
                        adapter.summary().c_str());
        }
    }
    return kExitOk;
}

int printModel(const InfoOptions& options, const GlobalOptions& global) {
    // Warnings are part of the summary, so the model is loaded without loadModel, which would
    // also print them to stderr.
    scene::LoadOptions loadOptions;
    loadOptions.allowUrisOutside = global.allowUrisOutside;
    auto scene = scene::loadScene(options.model, loadOptions);
    if (!scene) {
        return reportError(scene.error());
    }
    const scene::ModelSummary summary = scene::summarizeModel(*scene);
    if (options.json) {
        std::printf("%s\n", scene::modelSummaryJson(summary).dump(2).c_str());
    } else {
        std::printf("%s", scene::formatModelSummary(summary).c_str());
    }
    return kExitOk;
}

}  // namespace

void addInfoCommand(CLI::App& app, const GlobalOptions& global, int& exitCode) {
    auto options = std::make_shared<InfoOptions>();
    auto* command = app.add_subcommand("info",
                                       "Print the GPU adapters (the one Encore uses marked), or "
                                       "with MODEL what Encore loads from it.");
    command->add_option("model", options->model,
                        "A .gltf or .glb file: print its counts, extensions and warnings");
    command->add_flag("--json", options->json, "Print a JSON object instead of text");
    command->callback([&global, &exitCode, options] {
        exitCode = options->model.empty() ? printAdapters(global, options->json)
                                          : printModel(*options, global);
    });
}

}  // namespace encore::app
