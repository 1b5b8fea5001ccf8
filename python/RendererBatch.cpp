// encore.Renderer.batch: the keyword arguments (BatchKeywords.h) applied as `encore batch` applies
// its options, and the summary it returns.

#include <pybind11/stl.h>

#include <atomic>
#include <optional>
#include <tuple>

#include "BatchArguments.h"
#include "BatchKeywords.h"
#include "ModuleErrors.h"
#include "Renderer.h"
#include "batch/BatchOptionTable.h"
#include "batch/BatchOptionsValidation.h"
#include "batch/BatchRenderer.h"
#include "encore/batch/Batch.h"
#include "encore/batch/BatchInputs.h"

namespace encore::python {
namespace {

py::dict summaryDict(const batch::BatchSummary& result) {
    py::dict stages;
    stages["load"] = result.stages.load;
    stages["upload"] = result.stages.upload;
    stages["render"] = result.stages.render;
    stages["gpu"] = result.stages.gpu;
    stages["readback"] = result.stages.readback;
    stages["encode"] = result.stages.encode;
    stages["load_cpu"] = result.stages.loadCpu;
    stages["encode_cpu"] = result.stages.encodeCpu;
    py::list failures;
    for (const batch::Failure& failure : result.failures) {
        py::dict entry;
        entry["file"] = failure.file.string();
        entry["stage"] = failure.stage;
        // Messages may quote file contents: invalid UTF-8 is replaced, as failures.jsonl does.
        entry["error"] = py::reinterpret_steal<py::object>(PyUnicode_DecodeUTF8(
            failure.error.data(), Py_ssize_t(failure.error.size()), "replace"));
        failures.append(entry);
    }
    py::dict dict;
    dict["total"] = result.total;
    dict["rendered"] = result.rendered;
    dict["failed"] = result.failed;
    dict["skipped"] = result.skipped;
    dict["views"] = result.views;
    dict["seconds"] = result.seconds;
    dict["interrupted"] = result.interrupted;
    dict["loads_left_behind"] = result.loadsLeftBehind;
    dict["stages"] = stages;
    dict["failures"] = failures;
    py::list devices;
    for (const batch::DeviceSummary& device : result.devices) {
        py::dict entry;
        entry["device"] = device.device;
        entry["adapter"] = device.adapter;
        entry["models"] = device.models;
        entry["views"] = device.views;
        devices.append(entry);
    }
    dict["devices"] = devices;
    return dict;
}

}  // namespace

// Runs the job of `encore batch` on this renderer's device.
py::dict Renderer::runBatch(const py::object& inputs,
                            const std::string& output,
                            const py::kwargs& keywords) {
    batch::BatchOptions options;
    options.strategy = mStrategy;
    options.chooseStrategyPerModel = !mStrategy;  // "auto" or none given.
    options.samples = mSamples;                   // Unless samples= is given.
    options.output = output;
    const std::vector<batch::GivenOption> given = givenBatchOptions(keywords);
    Result<void> applied;
    {
        py::gil_scoped_release release;  // An environment= file is read here.
        applied = batch::applyBatchOptions(options, given, batch::OptionFront::Python);
        if (applied) {
            applied = batch::validateBatchOptions(options);
        }
    }
    if (!applied) {
        if (applied.error().code == ErrorCode::InvalidArgument) {
            throw py::value_error(applied.error().message);
        }
        throw EncoreError(applied.error().message);
    }
    const std::vector<batch::BatchInput> models = batchInputs(inputs);
    // Python runs signal handlers only when the interpreter gets the GIL back: look for one
    // as progress is reported. A KeyboardInterrupt (or a handler's exception) stops the
    // batch as SIGINT stops the command, the models in flight finished, and is raised after.
    std::atomic<bool> stop{false};
    std::optional<py::error_already_set> interrupt;
    options.stop = &stop;
    options.progress = [&](const batch::BatchProgress&) {
        py::gil_scoped_acquire acquire;
        if (!interrupt && PyErr_CheckSignals() != 0) {
            interrupt.emplace();  // Takes the exception out of the interpreter.
            stop = true;
        }
    };
    Result<batch::BatchSummary> summary = makeError(ErrorCode::InvalidArgument, "");
    {
        py::gil_scoped_release release;
        std::lock_guard lock(mMutex);  // One job on the device at a time.
        // The batch renderer of the previous call when the options allow: encore.dask calls
        // this once per task, and building it (environment maps, pipelines) would otherwise
        // cost every task as much as a few models.
        summary = batch::runBatch(*mBatchRenderers, models, options);
    }
    if (interrupt) {
        throw std::move(*interrupt);
    }
    return summaryDict(valueOrThrow(std::move(summary)));
}

}  // namespace encore::python
