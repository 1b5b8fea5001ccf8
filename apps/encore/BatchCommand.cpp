#include <time.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "BatchOptionsCli.h"
#include "BatchReport.h"
#include "Commands.h"
#include "DeviceOptions.h"
#include "batch/BatchOptionsValidation.h"
#include "batch/BatchRenderer.h"
#include "encore/batch/Batch.h"

namespace encore::app {

namespace {

// The command's own options; those of the batch are BatchOptionsCli's.
struct BatchCommandOptions {
    std::string input;
    std::string output;
    std::string devices;  // --devices all|N,M,...; empty: the global device.
    bool quiet = false;
    BatchOptionsCli batch;
};

// Set by SIGINT and SIGTERM: the batch starts no more models, writes the views in flight and
// returns. A second signal stops the process at once, unless it came with the first: timeout(1)
// signals its child and then the child's process group, so the batch gets each signal twice
// within microseconds, and the second used to kill it (exit 143) when a thread had taken the
// first in between.
std::atomic<bool> gStopRequested{false};
std::atomic<std::int64_t> gStopRequestedNs{0};
constexpr std::int64_t kSameStopRequestNs = 200'000'000;
static_assert(std::atomic<std::int64_t>::is_always_lock_free);

extern "C" void requestStop(int signal) {
    timespec now{};
    clock_gettime(CLOCK_MONOTONIC, &now);  // Async-signal-safe, as are the lock-free atomics.
    const std::int64_t ns = std::int64_t(now.tv_sec) * 1'000'000'000 + now.tv_nsec;
    if (!gStopRequested.exchange(true)) {
        gStopRequestedNs = ns;
        return;
    }
    if (ns - gStopRequestedNs < kSameStopRequestNs) {
        return;
    }
    std::signal(signal, SIG_DFL);
    std::raise(signal);
}

// The adapters of --devices, or the one --device (or ENCORE_DEVICE) names.
Result<std::vector<std::size_t>> batchDevices(const BatchCommandOptions& options,
                                              const GlobalOptions& global) {
    if (options.devices.empty()) {
        ENCORE_TRY_ASSIGN(auto device, chosenDevice(global));
        return std::vector<std::size_t>{device};
    }
    if (global.device) {
        return makeError(ErrorCode::InvalidArgument,
                         "--device and --devices exclude each other: --devices lists them all.");
    }
    ENCORE_TRY_ASSIGN(auto adapters, gpu::listAdapters(global.allowNullBackend));
    return parseDeviceList(options.devices, adapters);
}

int runBatch(const BatchCommandOptions& options, const GlobalOptions& global) {
    batch::BatchOptions batchOptions;
    batchOptions.output = options.output;
    // Usage errors before the device starts.
    if (auto applied = options.batch.applyTo(batchOptions, global); !applied) {
        return reportError(applied.error());
    }
    if (auto valid = batch::validateBatchOptions(batchOptions); !valid) {
        return reportError(valid.error());
    }

    auto inputs = batch::discoverInputs(options.input);
    if (!inputs) {
        return reportError(inputs.error());
    }
    // -v times the GPU's stages: timestamps need the device feature, asked for only then.
    batchOptions.gpuTimestamps = global.verbose;
    auto devices = batchDevices(options, global);
    if (!devices) {
        return reportError(devices.error());
    }
    // One context (device) and one set of renderers per entry of --devices.
    std::vector<gpu::Context> contexts;
    contexts.reserve(devices->size());
    for (std::size_t device : *devices) {
        auto context = createContext(global, /*timestamps=*/global.verbose, device);
        if (!context) {
            return reportError(context.error());
        }
        contexts.push_back(std::move(*context));
    }
    std::vector<std::unique_ptr<batch::BatchRenderer>> renderers;
    std::vector<batch::BatchRenderer*> deviceRenderers;
    for (gpu::Context& context : contexts) {
        renderers.push_back(std::make_unique<batch::BatchRenderer>(context));
        deviceRenderers.push_back(renderers.back().get());
    }

    // A live line on a terminal; every few seconds on a pipe or a file; none with --quiet.
    const bool terminal = ::isatty(STDERR_FILENO) == 1;
    const double interval = terminal ? 0.2 : 5.0;
    double lastPrinted = -interval;
    std::size_t startSkipped = 0;
    bool first = true;
    batchOptions.progress = [&](const batch::BatchProgress& progress) {
        if (first) {
            startSkipped = progress.skipped;  // Skipped models take no time: not in the ETA.
            first = false;
        }
        if (options.quiet || progress.seconds - lastPrinted < interval) {
            return;
        }
        lastPrinted = progress.seconds;
        const std::string line = progressLine(progress, startSkipped);
        std::fprintf(stderr, terminal ? "\r%s\033[K" : "%s\n", line.c_str());
    };
    gStopRequested = false;
    gStopRequestedNs = 0;
    batchOptions.stop = &gStopRequested;
    auto previousInt = std::signal(SIGINT, requestStop);
    auto previousTerm = std::signal(SIGTERM, requestStop);
    auto summary = batch::runBatch(deviceRenderers, *inputs, batchOptions);
    std::signal(SIGINT, previousInt);
    std::signal(SIGTERM, previousTerm);
    if (terminal && !options.quiet) {
        std::fprintf(stderr, "\n");
    }
    if (!summary) {
        return reportError(summary.error());
    }
    printBatchSummary(*summary,
                      batchOptions.jobs
                          ? batchOptions.jobs
                          : std::size_t(std::max(1u, std::thread::hardware_concurrency())),
                      global.verbose);
    if (summary->failed > 0) {
        std::fprintf(stderr, "error: %zu models failed; see %s\n", summary->failed,
                     (std::filesystem::path(options.output) / "failures.jsonl").c_str());
        return kExitFailure;
    }
    return summary->interrupted ? kExitInterrupted : kExitOk;
}

}  // namespace

void addBatchCommand(CLI::App& app, const GlobalOptions& global, int& exitCode) {
    auto options = std::make_shared<BatchCommandOptions>();
    auto* command = app.add_subcommand(
        "batch",
        "Render many glTF models from orbit or random viewpoints into a dataset folder: per "
        "model RGBA PNGs, a NeRF transforms.json and metadata.json; reruns skip finished "
        "models.");
    command
        ->add_option("input", options->input,
                     "A folder (searched recursively for .gltf/.glb), a model, a text file with "
                     "one path per line, or a JSON list of paths")
        ->required();
    command->add_option("-o,--output", options->output, "The output folder")->required();
    command
        ->add_option("--devices", options->devices,
                     "Render on several GPUs at once: all (every adapter like the first: the "
                     "GPUs, not a CPU renderer beside them) or indices as `encore info` lists "
                     "them (0,1,...; one listed twice gets two devices)")
        ->type_name("all|N,M,...");
    command->add_flag("-q,--quiet", options->quiet, "No progress lines");
    options->batch.addTo(*command);
    command->callback([options, &global, &exitCode] { exitCode = runBatch(*options, global); });
}

}  // namespace encore::app
