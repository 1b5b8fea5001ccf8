#pragma once

// Writes the files of the models a batch has in flight, on the thread pool, so that the device
// thread never waits for a PNG encoder or the disk: each view is cropped out of its read-back,
// encoded and written under its partial name; the last image of a model renames them all and
// writes transforms.json last (ModelOutput.h), so its presence says every image is in place.

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/ThreadPool.h"
#include "encore/batch/Batch.h"
#include "encore/batch/BatchInputs.h"
#include "encore/batch/FailureLog.h"
#include "encore/batch/ViewImages.h"
#include "encore/core/Result.h"
#include "encore/gpu/TextureReadbackRing.h"

namespace encore::batch {

// Counters the pool's encode tasks and the GPU thread both update.
struct SharedCounters {
    std::atomic<std::size_t> rendered{0};
    std::atomic<std::size_t> failed{0};
    // Found finished only once loaded (each sample's folder; BatchRun skips the others first).
    std::atomic<std::size_t> skipped{0};
    std::atomic<std::uint64_t> views{0};
    std::mutex mutex;  // Guards the sums below.
    double load = 0.0;
    double encode = 0.0;
    double loadCpu = 0.0;
    double encodeCpu = 0.0;
};

// What the samples of one model share (one sample, or one per material variant with
// BatchOptions::allVariants): the model counts as rendered once each of its samples is written,
// as failed once, with its first failure.
struct ModelProgress {
    const BatchInput* input = nullptr;
    std::atomic<std::uint32_t> remaining{0};  // Samples not yet written.
    std::atomic<bool> failed{false};

    void fail(FailureLog& log,
              SharedCounters& counters,
              const std::string& stage,
              const Error& error) {
        if (!failed.exchange(true)) {
            log.record(input->path, stage, error.message);
            ++counters.failed;
        }
    }
    // A sample's last file is written.
    void sampleWritten(SharedCounters& counters) {
        if (remaining.fetch_sub(1) == 1 && !failed) {
            ++counters.rendered;
        }
    }
};

// One sample of a model (its views in one set of materials) from its upload until its last
// file is written, shared by its encode tasks.
struct ModelJob {
    std::shared_ptr<ModelProgress> model;
    std::string variant;  // The KHR_materials_variants variant drawn; empty: the default.
    std::filesystem::path folder;
    std::vector<glm::mat4> cameraToWorld;
    std::atomic<std::uint32_t> remaining{0};  // Images not yet written.
    std::atomic<bool> failed{false};
    // Images written under their partial names, flushed and renamed together by the last one.
    std::mutex writtenMutex;
    std::vector<std::filesystem::path> written;

    // Records the sample's first failure as the model's (a variant's failure names it); later
    // ones (other views) add nothing.
    void fail(FailureLog& log,
              SharedCounters& counters,
              const std::string& stage,
              const Error& error) {
        if (!failed.exchange(true)) {
            model->fail(
                log, counters, stage,
                variant.empty() ? error : error.withContext("Material variant '" + variant + "'"));
        }
    }
};

// Creates a model's folder and removes the partial files a stopped run left in it, before the
// model's images are written afresh.
Result<void> openModelFolder(const std::filesystem::path& folder);

// Hands a model's images to `pool` and counts what it writes in `counters`; a model's first
// failure goes to `failures`. Everything it is given must outlive the tasks it submits.
class ModelWriter {
  public:
    ModelWriter(ThreadPool& pool,
                const BatchOptions& options,
                FailureLog& failures,
                SharedCounters& counters)
        : mPool(pool), mOptions(options), mFailures(failures), mCounters(counters) {}

    // Hands the views [first, first + count) of `job`, side by side in a read-back target, to
    // the pool; the ring has the buffer back once the last is cropped.
    void writeViews(const std::shared_ptr<ModelJob>& job,
                    std::uint32_t first,
                    std::uint32_t count,
                    ViewImage kind,
                    std::shared_ptr<const gpu::MappedReadback> wide);
    // Converts the views [first, first + count) of a target drawn through the depth channel
    // (Renderer::readHdrImage, `targetWidth` wide) into 16-bit depth images on the calling
    // thread, then encodes and writes them on the pool.
    void writeDepthViews(const std::shared_ptr<ModelJob>& job,
                         std::uint32_t first,
                         std::uint32_t count,
                         std::span<const float> wide,
                         std::uint32_t targetWidth,
                         float unitsPerModelUnit);

  private:
    // Crops strip `strip` of a read-back target on the pool, ahead of other tasks (the ring
    // waits for its buffer), then encodes it.
    void encodeView(const std::shared_ptr<ModelJob>& job,
                    std::uint32_t view,
                    ViewImage kind,
                    std::shared_ptr<const gpu::MappedReadback> wide,
                    std::uint32_t strip);
    // Encodes one image of `job` on the pool and writes it; the last one completes the model.
    void writeImage(const std::shared_ptr<ModelJob>& job,
                    std::uint32_t view,
                    ViewImage kind,
                    std::function<Result<std::vector<std::uint8_t>>()> encode);
    // Flushes and renames the model's images (or removes them if it failed), then writes
    // transforms.json.
    void finishImages(ModelJob& job);
    void writeTransforms(ModelJob& job);

    ThreadPool& mPool;
    const BatchOptions& mOptions;
    FailureLog& mFailures;
    SharedCounters& mCounters;
};

}  // namespace encore::batch
