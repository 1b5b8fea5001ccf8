#include "batch/ModelWriter.h"

#include <chrono>
#include <span>

#include "batch/ModelOutput.h"
#include "batch/TransformsJson.h"
#include "batch/ViewStrips.h"
#include "core/Elapsed.h"
#include "core/FileIO.h"
#include "encore/image/ImageCodec.h"

namespace encore::batch {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

}  // namespace

Result<void> openModelFolder(const fs::path& folder) {
    std::error_code ec;
    fs::create_directories(folder, ec);
    if (ec) {
        return makeError(ErrorCode::IoError, "Cannot create the folder '" + folder.string() +
                                                 "' (" + ec.message() + ").");
    }
    removePartialFiles(folder);
    return {};
}

void ModelWriter::writeTransforms(ModelJob& job) {
    const nlohmann::json json = transformsJson(glm::radians(mOptions.views.horizontalFovDegrees),
                                               mOptions.width, mOptions.height, job.cameraToWorld,
                                               mOptions.images, depthScale(mOptions.views));
    const std::string text = json.dump(2) + "\n";
    auto written = writeFileAtomically(
        job.folder / kTransformsFileName,
        std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
    if (!written) {
        job.fail(mFailures, mCounters, "write", written.error());
        return;
    }
    job.model->sampleWritten(mCounters);
}

void ModelWriter::writeViews(const std::shared_ptr<ModelJob>& job,
                             std::uint32_t first,
                             std::uint32_t count,
                             ViewImage kind,
                             std::shared_ptr<const gpu::MappedReadback> wide) {
    for (std::uint32_t strip = 0; strip < count; ++strip) {
        encodeView(job, first + strip, kind, wide, strip);
    }
}

void ModelWriter::writeDepthViews(const std::shared_ptr<ModelJob>& job,
                                  std::uint32_t first,
                                  std::uint32_t count,
                                  std::span<const float> wide,
                                  std::uint32_t targetWidth,
                                  float unitsPerModelUnit) {
    for (std::uint32_t strip = 0; strip < count; ++strip) {
        image::ImageGray16 depth =
            depthStrip(wide, targetWidth, strip, mOptions.width, mOptions.height, unitsPerModelUnit,
                       depthScale(mOptions.views));
        writeImage(job, first + strip, ViewImage::Depth,
                   [depth = std::move(depth), compression = mOptions.pngCompression] {
                       return image::encodePng16(depth, compression);
                   });
    }
}

void ModelWriter::encodeView(const std::shared_ptr<ModelJob>& job,
                             std::uint32_t view,
                             ViewImage kind,
                             std::shared_ptr<const gpu::MappedReadback> wide,
                             std::uint32_t strip) {
    mPool.submitFirst([this, job, view, kind, wide = std::move(wide), strip]() mutable {
        const auto start = Clock::now();
        const double cpuStart = threadCpuSeconds();
        auto image = std::make_shared<image::ImageRgba8>(
            cropStrip(wide->rows, wide->bytesPerRow, wide->height, strip, mOptions.width));
        wide.reset();  // The last strip lets the ring have its buffer back.
        {
            std::lock_guard lock(mCounters.mutex);
            mCounters.encode += secondsSince(start);
            mCounters.encodeCpu += threadCpuSeconds() - cpuStart;
        }
        writeImage(job, view, kind, [kind, image, compression = mOptions.pngCompression] {
            if (kind == ViewImage::Normal) {
                decodeNormalImage(*image);
            }
            return image::encodePng(*image, compression);
        });
    });
}

void ModelWriter::writeImage(const std::shared_ptr<ModelJob>& job,
                             std::uint32_t view,
                             ViewImage kind,
                             std::function<Result<std::vector<std::uint8_t>>()> encode) {
    mPool.submit([this, job, view, kind, encode = std::move(encode)] {
        const auto start = Clock::now();
        const double cpuStart = threadCpuSeconds();
        if (!job->failed) {
            auto png = encode();
            const fs::path path = viewImagePath(job->folder, view, kind);
            Result<void> written = png ? writePartialFile(path, *png) : Result<void>(png.error());
            if (!written) {
                job->fail(mFailures, mCounters, "write", written.error());
            } else {
                std::lock_guard lock(job->writtenMutex);
                job->written.push_back(path);
            }
            if (written && kind == ViewImage::Color) {
                ++mCounters.views;
            }
        }
        // The last image written completes the model: its images are flushed and renamed
        // together, then transforms.json goes last, so its presence says every image is in
        // place.
        if (job->remaining.fetch_sub(1) == 1) {
            finishImages(*job);
        }
        std::lock_guard lock(mCounters.mutex);
        mCounters.encode += secondsSince(start);
        mCounters.encodeCpu += threadCpuSeconds() - cpuStart;
    });
}

void ModelWriter::finishImages(ModelJob& job) {
    if (!job.failed) {
        if (auto committed = commitFiles(job.written); !committed) {
            job.fail(mFailures, mCounters, "write", committed.error());
        }
    }
    if (job.failed) {
        // A failed model leaves no partial files; its finished images are redone next run.
        for (const fs::path& path : job.written) {
            std::error_code ignored;
            fs::remove(partialPath(path), ignored);
        }
        return;
    }
    writeTransforms(job);
}

}  // namespace encore::batch
