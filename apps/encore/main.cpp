// encore: render glTF 2.0 scenes with WebGPU (Dawn) and measure how each rendering strategy
// performs. Parsing only; the commands live beside this file.

#include <cstdio>
#include <string>

#include "Commands.h"
#include "core/Log.h"
#include "encore/render/StrategyKind.h"

namespace {

std::string strategyList() {
    std::string list;
    for (auto kind : encore::render::allStrategies()) {
        list += list.empty() ? "" : ", ";
        list += encore::render::strategyName(kind);
    }
    return list;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace encore::app;
    GlobalOptions global;
    CLI::App app{"encore: render glTF 2.0 scenes with WebGPU through Dawn, strategy by strategy."};
    app.footer("Strategies: " + strategyList() +
               "\nExit codes: 0 success, 1 bad input or I/O error, 2 usage error, "
               "3 no Vulkan adapter, 4 WebGPU validation error or device loss, "
               "5 out of GPU memory, 6 no display (view), 130 interrupted (batch).");
    app.require_subcommand(1);
    app.add_flag("-v,--verbose", global.verbose, "Print the adapter and per-frame details");
    app.add_flag("--allow-null-backend", global.allowNullBackend,
                 "Accept Dawn's Null backend (validation only: images stay blank)");
    app.add_flag("--allow-uris-outside", global.allowUrisOutside,
                 "Let models read buffers and images outside their own folder (absolute paths, "
                 "'..', links that lead out): for trusted local trees only");
    app.add_option("--device", global.device,
                   "The adapter to render on, by its index in `encore info` (default: "
                   "$ENCORE_DEVICE, else 0, the adapter Dawn prefers)")
        ->check(CLI::NonNegativeNumber)
        ->type_name("N");
    // Global options may follow the subcommand: `encore render --device 1 model.glb`.
    app.fallthrough();

    int exitCode = kExitOk;
    addRenderCommand(app, global, exitCode);
    addInfoCommand(app, global, exitCode);
    addGenCommand(app, global, exitCode);
    addStatsCommand(app, global, exitCode);
    addBenchCommand(app, global, exitCode);
    addPlotCommand(app, global, exitCode);
    addCompareCommand(app, global, exitCode);
    addViewCommand(app, global, exitCode);
    addBatchCommand(app, global, exitCode);

    encore::setLogSink([&global](encore::LogLevel level, std::string_view message) {
        if (level == encore::LogLevel::Error) {
            std::fprintf(stderr, "error: %.*s\n", int(message.size()), message.data());
        } else if (level == encore::LogLevel::Warning) {
            // Loader warnings are printed by the commands from SceneData::warnings.
        } else if (global.verbose) {
            std::fprintf(stderr, "%.*s\n", int(message.size()), message.data());
        }
    });

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& error) {
        const int code = app.exit(error);
        return code == 0 ? kExitOk : kExitUsage;
    }
    return exitCode;
}
