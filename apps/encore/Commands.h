#pragma once

// The encore subcommands. main.cpp parses the command line; each command runs here and returns
// the process exit code. Only apps/ prints.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstddef>
#include <optional>
#include <string>

#include "encore/core/Result.h"
#include "encore/gpu/Context.h"
#include "encore/scene/SceneData.h"

namespace encore::app {

// Exit codes, documented in `encore --help` and the README.
enum ExitCode : int {
    kExitOk = 0,
    kExitFailure = 1,        // Bad input, I/O errors.
    kExitUsage = 2,          // Command-line errors.
    kExitNoAdapter = 3,      // No usable (Vulkan) GPU adapter.
    kExitGpuError = 4,       // WebGPU validation error or device loss.
    kExitOutOfMemory = 5,    // The GPU ran out of memory (a smaller scene or target may fit).
    kExitNoDisplay = 6,      // encore view: no display to open a window on.
    kExitInterrupted = 130,  // encore batch: stopped by SIGINT or SIGTERM (rerun to resume).
};

struct GlobalOptions {
    bool verbose = false;
    bool allowNullBackend = false;
    // --allow-uris-outside: models may read files outside their folder
    // (scene::LoadOptions::allowUrisOutside).
    bool allowUrisOutside = false;
    // --device N: the adapter of `encore info`'s list to render on; unset: ENCORE_DEVICE when
    // the environment sets it, otherwise 0 (the adapter Dawn prefers).
    std::optional<std::size_t> device;
};

// The adapter index the global options and the environment name (GlobalOptions::device), or
// a usage error when ENCORE_DEVICE is not a number.
Result<std::size_t> chosenDevice(const GlobalOptions& global);

// Prints "error: <message>" and returns the exit code for the error's code.
int reportError(const Error& error);

// Loads a model and prints its warnings ("warning: ...").
// With the global options' uri confinement.
Result<scene::SceneData> loadModel(const std::string& path,
                                   scene::LoadOptions options,
                                   const GlobalOptions& global);

// Creates the GPU context the global options ask for (on their device); prints the adapter with
// --verbose. `device` overrides the global choice (encore batch --devices).
Result<gpu::Context> createContext(const GlobalOptions& global,
                                   bool timestamps = false,
                                   std::optional<std::size_t> device = std::nullopt);

// Called once the scene is prepared. Tests of device loss set ENCORE_TEST_FORCE_DEVICE_LOSS: the
// commands then lose their device on purpose (Dawn's Device::ForceLoss). Tests of running out
// of GPU memory set ENCORE_TEST_INJECT_OUT_OF_MEMORY: Dawn then reports an out-of-memory error
// (Device::InjectError), as it does when an allocation fails.
void injectFaultsForTests(gpu::Context& context);

void addRenderCommand(CLI::App& app, const GlobalOptions& global, int& exitCode);
void addInfoCommand(CLI::App& app, const GlobalOptions& global, int& exitCode);
void addGenCommand(CLI::App& app, const GlobalOptions& global, int& exitCode);
void addStatsCommand(CLI::App& app, const GlobalOptions& global, int& exitCode);
void addBenchCommand(CLI::App& app, const GlobalOptions& global, int& exitCode);
void addPlotCommand(CLI::App& app, const GlobalOptions& global, int& exitCode);
void addCompareCommand(CLI::App& app, const GlobalOptions& global, int& exitCode);
void addViewCommand(CLI::App& app, const GlobalOptions& global, int& exitCode);
void addBatchCommand(CLI::App& app, const GlobalOptions& global, int& exitCode);

// Writes the scaling-curve SVG of a benchmark report; returns an exit code.
int writePlot(const nlohmann::json& report, const std::string& path);

}  // namespace encore::app
