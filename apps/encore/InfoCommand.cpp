// encore info [MODEL] [--json]: without a model, the GPU adapter Encore would use; with one, what
// the loader made of it (ModelInfo.h). The model summary never creates a GPU device, so it works
// on machines without a Vulkan adapter.

#include <cstdio>
#include <memory>
#include <string>

#include "Commands.h"
#include "ModelInfo.h"
#include "encore/gpu/Context.h"

namespace encore::app {
namespace {

struct InfoOptions {
    std::string model;
    bool json = false;
};

int printAdapter(const GlobalOptions& global, bool json) {
    auto context = createContext(global);
    if (!context) {
        return reportError(context.error());
    }
    const auto& adapter = context->adapterDescription();
    if (json) {
        const nlohmann::json report = {{"adapter", adapter.summary()},
                                       {"vendor", adapter.vendor},
                                       {"architecture", adapter.architecture}};
        std::printf("%s\n", report.dump(2).c_str());
    } else {
        std::printf("adapter: %s\n", adapter.summary().c_str());
        std::printf("vendor: %s\narchitecture: %s\n", adapter.vendor.c_str(),
                    adapter.architecture.c_str());
    }
    return kExitOk;
}

int printModel(const InfoOptions& options) {
    // Warnings are part of the summary, so the model is loaded without loadModel, which would
    // also print them to stderr.
    auto scene = scene::loadScene(options.model);
    if (!scene) {
        return reportError(scene.error());
    }
    const ModelSummary summary = summarizeModel(*scene);
    if (options.json) {
        std::printf("%s\n", modelSummaryJson(summary).dump(2).c_str());
    } else {
        std::printf("%s", formatModelSummary(summary).c_str());
    }
    return kExitOk;
}

}  // namespace

void addInfoCommand(CLI::App& app, const GlobalOptions& global, int& exitCode) {
    auto options = std::make_shared<InfoOptions>();
    auto* command = app.add_subcommand(
        "info", "Print the GPU adapter Encore would use, or with MODEL what Encore loads from it.");
    command->add_option("model", options->model,
                        "A .gltf or .glb file: print its counts, extensions and warnings");
    command->add_flag("--json", options->json, "Print a JSON object instead of text");
    command->callback([&global, &exitCode, options] {
        exitCode =
            options->model.empty() ? printAdapter(global, options->json) : printModel(*options);
    });
}

}  // namespace encore::app
