#pragma once

// Writes the files of the models a batch has in flight, on the thread pool, so that the device
// thread never waits for a PNG encoder or the disk: each view is cropped out of its read-back
// (its covered pixels counted on the way: blank views), encoded and written under its partial
// name; once the last image is written and the device thread is done with the model, its images
// (and camera matrices) are renamed together, then metadata.json and transforms.json are written,
// transforms.json last (ModelOutput.h), so its presence says every file is in place.

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

#include "batch/FailureLog.h"
#include "batch/ModelMetadata.h"
#include "batch/PassImages.h"
#include "batch/PngRowsPass.h"
#include "core/ThreadPool.h"
#include "encore/batch/Batch.h"
#include "encore/batch/BatchInputs.h"
#include "encore/batch/ViewImages.h"
#include "encore/core/Result.h"
#include "gpu/TextureReadbackRing.h"

namespace encore::batch {

class ShardWriter;

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
    // A device loss interrupted it: the device thread draws it again (DeviceLane::failJob).
    bool retry = false;
    bool retried = false;  // This is that second attempt.

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
    std::vector<ViewCamera> views;
    ModelLighting lighting;
    // The model's normalisation (ViewRig.h), set by the device thread: its scale is the depth's
    // unit with --depth-unit model, the box it fills the object coordinates' (--coordinates).
    glm::mat4 normalization{1.0f};
    ModelFacts facts;  // From the loader.
    // What the segmentation ids name (--segmentation), for transforms.json.
    std::vector<SegmentationName> segmentation;
    // load, upload and render are set by the device thread before it lets the model finish
    // (ModelWriter::rendered); encode is summed by the pool under writtenMutex.
    ModelTimes times;
    ModelDrawing drawing;  // Set by the device thread.
    // Covered pixels of each colour view, counted by the task that encodes it; empty when not
    // counted (ModelPlanner).
    std::vector<std::uint64_t> coveredPixels;
    // Images not yet written, and one more until the device thread calls ModelWriter::rendered.
    std::atomic<std::uint32_t> remaining{0};
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
    // With `shards`, each finished sample goes into a shard (ShardWriter.h) before it counts.
    ModelWriter(ThreadPool& pool,
                const BatchOptions& options,
                FailureLog& failures,
                SharedCounters& counters,
                ShardWriter* shards = nullptr)
        : mPool(pool),
          mOptions(options),
          mFailures(failures),
          mCounters(counters),
          mShards(shards) {}

    // Hands the views [first, first + count) of `job`, side by side in a read-back target, to
    // the pool; the ring has the buffer back once the last is cropped.
    void writeViews(const std::shared_ptr<ModelJob>& job,
                    std::uint32_t first,
                    std::uint32_t count,
                    ViewImage kind,
                    std::shared_ptr<const gpu::MappedReadback> wide);
    // The device thread has handed on every image of `job` (and set its times): once they are
    // written, the model finishes (on the pool). Once per job, after `remaining` was set to its
    // images plus one.
    void rendered(const std::shared_ptr<ModelJob>& job);
    // Converts the views [first, first + count) of a target read back as floats
    // (Renderer::readHdrImage, `targetWidth` wide) into `kind`'s images (Depth, Segmentation,
    // Hdr: PassImages.h) on the calling thread, then encodes and writes them on the pool.
    void writeFloatViews(const std::shared_ptr<ModelJob>& job,
                         std::uint32_t first,
                         std::uint32_t count,
                         ViewImage kind,
                         std::span<const float> wide,
                         std::uint32_t targetWidth,
                         float unitsPerModelUnit);

    // The same from a read through the ring (half floats, gpu::MappedReadback::bytesPerTexel
    // 8), each strip converted on the pool, one image per kind in `kinds`: Hdr reads the scene
    // colour (RGBA), Depth and Segmentation the pass target that holds depth, the id % 256, the
    // id / 256 and coverage (render::PassImage::DepthAndId).
    void writeMappedFloatViews(const std::shared_ptr<ModelJob>& job,
                               std::uint32_t first,
                               std::uint32_t count,
                               std::vector<ViewImage> kinds,
                               std::shared_ptr<const gpu::MappedReadback> wide,
                               float unitsPerModelUnit);
    // The same for a read of PNG rows filtered on the GPU (PngRowsPass): each image of each
    // view compressed straight from the mapped buffer, which the ring has back once the last
    // is compressed.
    void writePngRowViews(const std::shared_ptr<ModelJob>& job,
                          std::uint32_t first,
                          std::uint32_t count,
                          PngRowsLayout layout,
                          std::shared_ptr<const gpu::MappedReadback> wide);

    // Encodes a file of the model that is not a view's (points.ply) on the pool and writes it
    // into its folder as `name`, renamed with the images; it counts among `remaining`.
    void writeModelFile(const std::shared_ptr<ModelJob>& job,
                        const std::string& name,
                        std::function<Result<std::vector<std::uint8_t>>()> encode);

  private:
    // How a float image of `kind` is encoded from `pixels` of `view` (ids packed as in a
    // DepthAndId pass target with `packedIds`, else as the segmentation channels write them) of
    // a model normalised by `normalization`.
    std::function<Result<std::vector<std::uint8_t>>()> floatEncoder(
        ViewImage kind,
        const FloatStrip& pixels,
        float unitsPerModelUnit,
        bool packedIds,
        const ViewCamera& view,
        const glm::mat4& normalization) const;
    // Crops strip `strip` of a read-back target on the pool, ahead of other tasks (the ring
    // waits for its buffer), then encodes it.
    void encodeView(const std::shared_ptr<ModelJob>& job,
                    std::uint32_t view,
                    ViewImage kind,
                    std::shared_ptr<const gpu::MappedReadback> wide,
                    std::uint32_t strip);
    // Records how many pixels colour view `view` covers; with --strict, a blank view fails the
    // model (stage "blank").
    void checkCoverage(ModelJob& job,
                       std::uint32_t view,
                       std::uint64_t covered,
                       std::uint64_t pixels);
    // Encodes one image of `job` on the pool and writes it; the last one completes the model.
    void writeImage(const std::shared_ptr<ModelJob>& job,
                    std::uint32_t view,
                    ViewImage kind,
                    std::function<Result<std::vector<std::uint8_t>>()> encode);
    // The same for any file at `path`; `colorView` counts it as a view written.
    void writeFile(const std::shared_ptr<ModelJob>& job,
                   std::filesystem::path path,
                   bool colorView,
                   std::function<Result<std::vector<std::uint8_t>>()> encode);
    // Writes the camera matrices (OutputLayout::Objaverse), flushes and renames them with the
    // model's images (or removes them all if it failed), then writes metadata.json and
    // transforms.json.
    void finishImages(ModelJob& job);
    Result<void> writeCameraMatrices(ModelJob& job);
    // The camera files (OutputLayout::Gobjaverse), the same way.
    Result<void> writeCameraFiles(ModelJob& job);
    void writeMetadata(ModelJob& job);
    void writeTransforms(ModelJob& job);

    ThreadPool& mPool;
    const BatchOptions& mOptions;
    FailureLog& mFailures;
    SharedCounters& mCounters;
    ShardWriter* mShards;
};

}  // namespace encore::batch
