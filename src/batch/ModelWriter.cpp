#include "batch/ModelWriter.h"

#include <chrono>
#include <span>

#include "batch/CameraConvention.h"
#include "batch/DepthConventions.h"
#include "batch/ExrFile.h"
#include "batch/ModelOutput.h"
#include "batch/NormalConventions.h"
#include "batch/NpyFile.h"
#include "batch/ObjaverseCamera.h"
#include "batch/ObjectCoordinates.h"
#include "batch/OptionNames.h"
#include "batch/PointCloud.h"
#include "batch/ShardWriter.h"
#include "batch/TransformsJson.h"
#include "batch/ViewStrips.h"
#include "core/Elapsed.h"
#include "core/FileIO.h"
#include "encore/image/ImageCodec.h"

namespace encore::batch {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

Result<void> writeJson(const fs::path& path, const nlohmann::json& json) {
    const std::string text =
        json.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
    return writeFileAtomically(
        path, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

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

namespace {

// metadata.json's "camera": the projection, the axes of each written camera file, and where the
// cameras came from (a preset, a pose file).
nlohmann::json cameraMetadata(const BatchOptions& options) {
    const ViewRigOptions& rig = options.views;
    nlohmann::json camera;
    camera["projection"] = std::string(nameOf(projectionNames(), rig.projection));
    if (rig.projection == Projection::Orthographic) {
        camera["orthoScale"] = double(rig.orthoScale);
    }
    camera["convention"] = {
        {"transforms",
         std::string(nameOf(cameraConventionNames(),
                            options.cameraConvention.value_or(CameraConvention::OpenGl)))}};
    if (options.layout == OutputLayout::Objaverse) {
        camera["convention"]["npy"] = std::string(nameOf(
            cameraConventionNames(), options.cameraConvention.value_or(CameraConvention::Blender)));
    }
    if (options.layout == OutputLayout::Gobjaverse) {
        camera["convention"]["cameraFiles"] = std::string(nameOf(
            cameraConventionNames(), options.cameraConvention.value_or(CameraConvention::OpenCv)));
    }
    camera["poses"] = rig.poses.empty() ? nlohmann::json(nullptr) : nlohmann::json(rig.posesFile);
    camera["preset"] =
        options.preset.empty() ? nlohmann::json(nullptr) : nlohmann::json(options.preset);
    return camera;
}

// metadata.json's "passes": what each extra pass's values mean (docs/batch.md#conventions), for
// the passes written.
nlohmann::json passMetadata(const ExtraImages& images) {
    nlohmann::json passes = nlohmann::json::object();
    if (images.depth) {
        passes["depth"] = {{"kind", std::string(nameOf(depthKindNames(), images.depthKind))},
                           {"unit", std::string(nameOf(depthUnitNames(), images.depthUnit))},
                           {"format", std::string(nameOf(depthFormatNames(), images.depthFormat))}};
    }
    if (images.normals) {
        passes["normal"] = {
            {"space", std::string(nameOf(normalSpaceNames(), images.normalSpace))},
            {"kind", std::string(nameOf(normalKindNames(), images.normalKind))},
            {"format", std::string(nameOf(normalFormatNames(), images.normalFormat))}};
    }
    if (images.coordinates) {
        passes["coordinates"] = {
            {"space", "normalized box in [0, 1]^3"},
            {"format", std::string(nameOf(coordinatesFormatNames(), images.coordinatesFormat))}};
    }
    return passes;
}

}  // namespace

void ModelWriter::writeMetadata(ModelJob& job) {
    std::lock_guard lock(job.writtenMutex);  // The encode times.
    nlohmann::json json = metadataJson(
        *job.model->input, job.facts, job.times, std::uint32_t(job.views.size()), job.coveredPixels,
        mOptions.blankThreshold, job.drawing, cameraMetadata(mOptions));
    if (nlohmann::json passes = passMetadata(mOptions.images); !passes.empty()) {
        json["passes"] = std::move(passes);
    }
    if (mOptions.pointCloudPoints > 0) {
        json["pointCloud"] = {{"file", kPointCloudFileName},
                              {"points", mOptions.pointCloudPoints},
                              {"format", "binary_little_endian"},
                              {"frame", "normalized"}};
    }
    if (auto written = writeJson(job.folder / kMetadataFileName, json); !written) {
        job.fail(mFailures, mCounters, "write", written.error());
    }
}

void ModelWriter::writeTransforms(ModelJob& job) {
    // With --depth-unit model a PNG holds the normalised steps; its scale says what they are in
    // the model's units.
    const double scale = mOptions.images.depthUnit == DepthUnit::Model
                             ? depthScale(mOptions.views) / double(job.normalization[0][0])
                             : depthScale(mOptions.views);
    nlohmann::json json = transformsJson(
        job.views, mOptions.width, mOptions.height, mOptions.images, scale, &job.lighting,
        job.segmentation, mOptions.cameraConvention.value_or(CameraConvention::OpenGl));
    if (mOptions.pointCloudPoints > 0) {
        json["point_cloud_path"] = std::string("./") + kPointCloudFileName;
    }
    if (auto written = writeJson(job.folder / kTransformsFileName, json); !written) {
        job.fail(mFailures, mCounters, "write", written.error());
        return;
    }
    if (mShards) {
        const std::string sample = fs::relative(job.folder, mOptions.output).generic_string();
        if (auto added = mShards->add(sample); !added) {
            job.fail(mFailures, mCounters, "write", added.error());
            return;
        }
    }
    job.model->sampleWritten(mCounters);
}

Result<void> ModelWriter::writeCameraMatrices(ModelJob& job) {
    for (std::size_t view = 0; view < job.views.size(); ++view) {
        const std::array<double, 12> matrix =
            worldToCameraRows(job.views[view].cameraToWorld,
                              mOptions.cameraConvention.value_or(CameraConvention::Blender));
        const fs::path path = cameraMatrixPath(job.folder, view);
        ENCORE_TRY(writePartialFile(path, npyFloat64(matrix, 3, 4)));
        job.written.push_back(path);
    }
    return {};
}

Result<void> ModelWriter::writeCameraFiles(ModelJob& job) {
    const CameraConvention convention =
        mOptions.cameraConvention.value_or(CameraConvention::OpenCv);
    for (std::size_t view = 0; view < job.views.size(); ++view) {
        const std::string text =
            cameraFileJson(job.views[view], convention, mOptions.width, mOptions.height).dump(2);
        const fs::path path = cameraFilePath(job.folder, view);
        ENCORE_TRY(writePartialFile(
            path, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size())));
        job.written.push_back(path);
    }
    return {};
}

void ModelWriter::checkCoverage(ModelJob& job,
                                std::uint32_t view,
                                std::uint64_t covered,
                                std::uint64_t pixels) {
    job.coveredPixels[view] = covered;  // Each view's task writes its own element.
    if (mOptions.strict && covered < mOptions.blankThreshold) {
        job.fail(mFailures, mCounters, "blank",
                 makeError(ErrorCode::InvalidFormat,
                           "View " + std::to_string(view) + " is blank: " +
                               std::to_string(covered) + " of its " + std::to_string(pixels) +
                               " pixels are covered, fewer than the blank threshold (" +
                               std::to_string(mOptions.blankThreshold) + ")."));
    }
}

void ModelWriter::rendered(const std::shared_ptr<ModelJob>& job) {
    if (job->remaining.fetch_sub(1) == 1) {
        // Every image is written: finish on the pool, which flushes files, not on the device
        // thread.
        mPool.submit([this, job] { finishImages(*job); });
    }
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

void ModelWriter::writeFloatViews(const std::shared_ptr<ModelJob>& job,
                                  std::uint32_t first,
                                  std::uint32_t count,
                                  ViewImage kind,
                                  std::span<const float> wide,
                                  std::uint32_t targetWidth,
                                  float unitsPerModelUnit) {
    for (std::uint32_t strip = 0; strip < count; ++strip) {
        const FloatStrip pixels{wide, targetWidth, strip, mOptions.width, mOptions.height};
        writeImage(job, first + strip, kind,
                   floatEncoder(kind, pixels, unitsPerModelUnit, /*packedIds=*/false,
                                job->views[first + strip], job->normalization));
    }
}

void ModelWriter::writeMappedFloatViews(const std::shared_ptr<ModelJob>& job,
                                        std::uint32_t first,
                                        std::uint32_t count,
                                        std::vector<ViewImage> kinds,
                                        std::shared_ptr<const gpu::MappedReadback> wide,
                                        float unitsPerModelUnit) {
    for (std::uint32_t strip = 0; strip < count; ++strip) {
        mPool.submitFirst(
            [this, job, view = first + strip, kinds, wide, strip, unitsPerModelUnit]() mutable {
                const auto start = Clock::now();
                const double cpuStart = threadCpuSeconds();
                const std::vector<float> texels = halfStrip(*wide, strip, mOptions.width);
                wide.reset();  // The last strip lets the ring have its buffer back.
                const FloatStrip pixels{texels, mOptions.width, 0, mOptions.width, mOptions.height};
                std::vector<std::function<Result<std::vector<std::uint8_t>>()>> encoders;
                for (const ViewImage kind : kinds) {
                    encoders.push_back(floatEncoder(kind, pixels, unitsPerModelUnit, true,
                                                    job->views[view], job->normalization));
                }
                const double seconds = secondsSince(start);
                {
                    std::lock_guard lock(mCounters.mutex);
                    mCounters.encode += seconds;
                    mCounters.encodeCpu += threadCpuSeconds() - cpuStart;
                }
                {
                    std::lock_guard lock(job->writtenMutex);
                    job->times.encode += seconds;
                }
                for (std::size_t i = 0; i < kinds.size(); ++i) {
                    writeImage(job, view, kinds[i], std::move(encoders[i]));
                }
            });
    }
}

void ModelWriter::writePngRowViews(const std::shared_ptr<ModelJob>& job,
                                   std::uint32_t first,
                                   std::uint32_t count,
                                   PngRowsLayout layout,
                                   std::shared_ptr<const gpu::MappedReadback> wide) {
    const auto rows = std::make_shared<const PngRowsLayout>(std::move(layout));
    for (std::uint32_t strip = 0; strip < count; ++strip) {
        const std::uint32_t view = first + strip;
        for (std::size_t i = 0; i < rows->images.size(); ++i) {
            const PngRowsLayout::Image& image = rows->images[i];
            if (image.kind == ViewImage::Color && !job->coveredPixels.empty()) {
                checkCoverage(*job, view, rows->coveredPixels(wide->rows, strip),
                              std::uint64_t(rows->width) * rows->height);
            }
            writeImage(job, view, image.kind, [rows, wide, i, strip] {
                const PngRowsLayout::Image& image = rows->images[i];
                return image::pngOfFilteredRows(rows->width, rows->height, image.bitDepth,
                                                image.color, rows->rows(wide->rows, i, strip),
                                                image.compression);
            });
        }
    }
}

std::function<Result<std::vector<std::uint8_t>>()> ModelWriter::floatEncoder(
    ViewImage kind,
    const FloatStrip& pixels,
    float unitsPerModelUnit,
    bool packedIds,
    const ViewCamera& view,
    const glm::mat4& normalization) const {
    const std::uint32_t width = pixels.width;
    const std::uint32_t height = pixels.height;
    const auto compression = mOptions.pngCompression;
    if (kind == ViewImage::Hdr) {
        return [rgba = hdrPixels(pixels), width, height] {
            return encodeExrRgbaHalf(rgba, width, height);
        };
    }
    if (kind == ViewImage::Segmentation) {
        return [ids = packedIds ? segmentationIdsOfPassTarget(pixels) : segmentationIds(pixels),
                compression = pngCompressionOf(kind, compression)] {
            return image::encodePng16(ids, compression);
        };
    }
    const ExtraImages& images = mOptions.images;
    if (kind == ViewImage::Coordinates) {
        return [coordinates = objectCoordinates(pixels, normalization), width, height,
                format = images.coordinatesFormat, compression] {
            return encodeCoordinates(coordinates, width, height, format, compression);
        };
    }
    if (kind == ViewImage::Normal) {
        const glm::dmat3 rotation = normalRotation(
            view, images.normalSpace, mOptions.cameraConvention.value_or(CameraConvention::OpenGl));
        return
            [normals = normalVectors(pixels, rotation), width, height, format = images.normalFormat,
             compression] { return encodeNormals(normals, width, height, format, compression); };
    }
    if (images.depthFormat == DepthFormat::Exr || images.depthKind == DepthKind::Ray) {
        // With --depth-unit model a PNG keeps the normalised steps (its depth_scale is the
        // model's, TransformsJson): only EXR values change unit.
        const bool exr = images.depthFormat == DepthFormat::Exr;
        std::vector<float> depth = depthOfKind(
            pixels, images.depthKind,
            exr ? depthUnitsPerModelUnit(images.depthUnit, unitsPerModelUnit) : unitsPerModelUnit,
            view);
        if (exr) {
            return [depth = std::move(depth), width, height] {
                return encodeExrDepth(depth, width, height);
            };
        }
        return [steps = depthStepsOf(depth, width, height, depthScale(mOptions.views)),
                compression] { return image::encodePng16(steps, compression); };
    }
    return [depth = depthStrip(pixels.wide, pixels.targetWidth, pixels.strip, width, height,
                               unitsPerModelUnit, depthScale(mOptions.views)),
            compression] { return image::encodePng16(depth, compression); };
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
        if (kind == ViewImage::Color && !job->coveredPixels.empty()) {
            checkCoverage(*job, view, coveredPixels(image->pixels),
                          std::uint64_t(image->width) * image->height);
        }
        const double seconds = secondsSince(start);
        {
            std::lock_guard lock(mCounters.mutex);
            mCounters.encode += seconds;
            mCounters.encodeCpu += threadCpuSeconds() - cpuStart;
        }
        {
            std::lock_guard lock(job->writtenMutex);
            job->times.encode += seconds;
        }
        writeImage(job, view, kind, [kind, image, compression = mOptions.pngCompression] {
            // Both are linear values that the sRGB output encoded.
            if (kind == ViewImage::Normal || kind == ViewImage::Material) {
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
    writeFile(job, viewImagePath(job->folder, view, kind, mOptions.images),
              kind == ViewImage::Color, std::move(encode));
}

void ModelWriter::writeModelFile(const std::shared_ptr<ModelJob>& job,
                                 const std::string& name,
                                 std::function<Result<std::vector<std::uint8_t>>()> encode) {
    writeFile(job, job->folder / name, /*colorView=*/false, std::move(encode));
}

void ModelWriter::writeFile(const std::shared_ptr<ModelJob>& job,
                            fs::path path,
                            bool colorView,
                            std::function<Result<std::vector<std::uint8_t>>()> encode) {
    mPool.submit([this, job, path = std::move(path), colorView, encode = std::move(encode)] {
        const auto start = Clock::now();
        const double cpuStart = threadCpuSeconds();
        if (!job->failed) {
            auto png = encode();
            Result<void> written = png ? writePartialFile(path, *png) : Result<void>(png.error());
            if (!written) {
                job->fail(mFailures, mCounters, "write", written.error());
            } else {
                std::lock_guard lock(job->writtenMutex);
                job->written.push_back(path);
            }
            if (written && colorView) {
                ++mCounters.views;
            }
        }
        {
            std::lock_guard lock(job->writtenMutex);
            job->times.encode += secondsSince(start);
        }
        // The last image written completes the model (unless the device thread still holds
        // it: ModelWriter::rendered): its images are flushed and renamed together, then
        // metadata.json and transforms.json go last, so the presence of transforms.json says
        // every file is in place.
        if (job->remaining.fetch_sub(1) == 1) {
            finishImages(*job);
        }
        std::lock_guard lock(mCounters.mutex);
        mCounters.encode += secondsSince(start);
        mCounters.encodeCpu += threadCpuSeconds() - cpuStart;
    });
}

void ModelWriter::finishImages(ModelJob& job) {
    if (!job.failed && mOptions.layout == OutputLayout::Objaverse) {
        if (auto written = writeCameraMatrices(job); !written) {
            job.fail(mFailures, mCounters, "write", written.error());
        }
    }
    if (!job.failed && mOptions.layout == OutputLayout::Gobjaverse) {
        if (auto written = writeCameraFiles(job); !written) {
            job.fail(mFailures, mCounters, "write", written.error());
        }
    }
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
    writeMetadata(job);
    if (!job.failed) {
        writeTransforms(job);
    }
}

}  // namespace encore::batch
