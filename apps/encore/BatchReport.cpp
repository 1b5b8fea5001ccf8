#include "BatchReport.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "encore/core/ReusedBlocks.h"
#include "render/GpuStage.h"

namespace encore::app {

namespace {

std::string duration(double seconds) {
    char text[32];
    if (!std::isfinite(seconds) || seconds < 0.0) {
        return "--";
    }
    const long total = long(seconds + 0.5);
    std::snprintf(text, sizeof(text), "%ld:%02ld:%02ld", total / 3600, total / 60 % 60, total % 60);
    return text;
}

// "gpu (s, timestamps): mipmaps 1.23 (1.2 ms per model, 33 passes per model), ..."
void printGpuStages(const std::vector<batch::GpuStageTime>& stages, std::size_t models) {
    if (stages.empty()) {
        std::printf("gpu: no timestamps (the device has no timestamp queries)\n");
        return;
    }
    const double perModel = models > 0 ? 1.0 / double(models) : 0.0;
    std::string line = "gpu (s, timestamps";
    line += models > 0 ? "; ms and passes per model" : "";
    line += "):";
    double total = 0.0;
    for (std::size_t stage = 0; stage < stages.size(); ++stage) {
        const batch::GpuStageTime& time = stages[stage];
        char part[160];
        std::snprintf(part, sizeof(part), "%s %s %.2f (%.2f ms, %.1f)", stage == 0 ? "" : ",",
                      std::string(render::kGpuStageNames[stage]).c_str(),
                      time.milliseconds / 1000.0, time.milliseconds * perModel,
                      double(time.timed) * perModel);
        line += part;
        if (time.untimed > 0) {
            line += " [" + std::to_string(time.untimed) + " untimed]";
        }
        total += time.milliseconds;
    }
    char sum[96];
    std::snprintf(sum, sizeof(sum), "; together %.2f (%.2f ms per model)", total / 1000.0,
                  total * perModel);
    std::printf("%s%s\n", line.c_str(), sum);
}

}  // namespace

std::string progressLine(const batch::BatchProgress& progress, std::size_t startSkipped) {
    const double viewsPerSecond =
        progress.seconds > 0.0 ? double(progress.views) / progress.seconds : 0.0;
    const std::size_t attempted = progress.done() - startSkipped;
    const std::size_t left = progress.total - progress.done();
    const double eta = attempted > 0 ? progress.seconds / double(attempted) * double(left) : NAN;
    char line[256];
    std::snprintf(line, sizeof(line), "%zu/%zu models, %zu failed, %.1f views/s, ETA %s",
                  progress.done(), progress.total, progress.failed, viewsPerSecond,
                  duration(eta).c_str());
    return line;
}

void printBatchSummary(const batch::BatchSummary& summary, std::size_t threads, bool verbose) {
    const double viewsPerSecond =
        summary.seconds > 0.0 ? double(summary.views) / summary.seconds : 0.0;
    std::printf(
        "%zu rendered, %zu failed, %zu skipped of %zu models; %llu views in %.2f s "
        "(%.1f views/s)%s\n",
        summary.rendered, summary.failed, summary.skipped, summary.total,
        static_cast<unsigned long long>(summary.views), summary.seconds, viewsPerSecond,
        summary.interrupted ? "; interrupted, run again to resume" : "");
    if (summary.loadsLeftBehind > 0) {
        std::fprintf(stderr,
                     "warning: %zu model loads did not stop when cancelled (a file stuck in the "
                     "kernel, such as one on a hung mount); their threads were left behind\n",
                     summary.loadsLeftBehind);
    }
    const batch::StageTimes& stages = summary.stages;
    std::printf(
        "stages (s): load+decode %.2f (cpu %.2f), upload %.2f (staging %.2f), render %.2f, gpu "
        "wait %.2f, read-back %.2f, encode+write %.2f (cpu %.2f) (load and encode summed over "
        "%zu threads, cpu: their CPU time without waiting for a core or the disk; the GPU works "
        "beside the upload, render and read-back)\n",
        stages.load, stages.loadCpu, stages.upload, stages.staging, stages.render, stages.gpu,
        stages.readback, stages.encode, stages.encodeCpu, threads);
    if (summary.devices.size() > 1 || verbose) {
        for (const batch::DeviceSummary& device : summary.devices) {
            std::printf("device %zu (%s): %llu models, %llu views%s%s\n", device.device,
                        device.adapter.c_str(), static_cast<unsigned long long>(device.models),
                        static_cast<unsigned long long>(device.views),
                        device.passTargets ? ", passes drawn in the colour pass" : "",
                        device.pngRowsOnGpu ? ", PNG rows filtered on the GPU" : "");
            if (verbose) {
                std::printf(
                    "device %zu created: %llu GPU objects, %.1f MiB mappable, by %llu of its "
                    "%llu models\n",
                    device.device, static_cast<unsigned long long>(device.gpuObjectsCreated),
                    double(device.gpuBytesMapped) / double(1 << 20),
                    static_cast<unsigned long long>(device.modelsCreatingGpuObjects),
                    static_cast<unsigned long long>(device.models));
            }
        }
    }
    if (verbose) {
        const ReusedBlockCounts blocks = reusedBlockCounts();
        std::printf("image blocks: %llu taken, %llu created (%.1f MiB), %.1f MiB kept for reuse\n",
                    static_cast<unsigned long long>(blocks.taken),
                    static_cast<unsigned long long>(blocks.created),
                    double(blocks.createdBytes) / double(1 << 20),
                    double(blocks.keptBytes) / double(1 << 20));
        const render::PrepareTimes& parts = stages.uploadParts;
        const double sceneOther = parts.scene - parts.geometry - parts.instances - parts.materials;
        const double strategyOther = parts.strategy - parts.draws;
        std::printf(
            "upload (s): release %.2f, lights+animation %.2f, geometry %.2f, instances %.2f, "
            "materials %.2f, other scene %.2f, draws+pipelines %.2f, other strategy %.2f, error "
            "checks %.2f\n",
            parts.release / 1000.0, parts.animation / 1000.0, parts.geometry / 1000.0,
            parts.instances / 1000.0, parts.materials / 1000.0, sceneOther / 1000.0,
            parts.draws / 1000.0, strategyOther / 1000.0, parts.checks / 1000.0);
        std::printf(
            "materials (s): texture creation %.2f, texture writes %.2f, mipmaps %.2f, submit "
            "%.2f\n",
            parts.textureCreation / 1000.0, parts.textureWrites / 1000.0, parts.mipmaps / 1000.0,
            parts.materialSubmit / 1000.0);
        printGpuStages(stages.gpuStages, summary.rendered + summary.failed);
    }
}

}  // namespace encore::app
