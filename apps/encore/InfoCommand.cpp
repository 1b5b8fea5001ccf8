#include <cstdio>

#include "Commands.h"
#include "encore/gpu/Context.h"

namespace encore::app {

void addInfoCommand(CLI::App& app, const GlobalOptions& global, int& exitCode) {
    auto* command = app.add_subcommand("info", "Print the GPU adapter Encore would use.");
    command->callback([&global, &exitCode] {
        auto context = createContext(global);
        if (!context) {
            exitCode = reportError(context.error());
            return;
        }
        const auto& adapter = context->adapterDescription();
        std::printf("adapter: %s\n", adapter.summary().c_str());
        std::printf("vendor: %s\narchitecture: %s\n", adapter.vendor.c_str(),
                    adapter.architecture.c_str());
        exitCode = kExitOk;
    });
}

}  // namespace encore::app
