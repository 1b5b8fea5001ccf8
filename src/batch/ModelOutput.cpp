#include "batch/ModelOutput.h"

#include "batch/ModelMetadata.h"
#include "batch/PointCloud.h"

namespace encore::batch {

namespace fs = std::filesystem;

fs::path modelFolder(const fs::path& output, const std::string& name) {
    return output / fs::path(name);
}

fs::path viewImagePath(const fs::path& folder,
                       std::size_t index,
                       ViewImage kind,
                       const ExtraImages& extras) {
    return folder / (viewStem(index, kind) + viewExtension(kind, extras));
}

std::vector<ViewImage> extraPasses(const ExtraImages& extras) {
    std::vector<ViewImage> passes;
    const std::pair<bool, ViewImage> asked[] = {{extras.normals, ViewImage::Normal},
                                                {extras.depth, ViewImage::Depth},
                                                {extras.albedo, ViewImage::Albedo},
                                                {extras.material, ViewImage::Material},
                                                {extras.segmentation, ViewImage::Segmentation},
                                                {extras.hdr, ViewImage::Hdr},
                                                {extras.coordinates, ViewImage::Coordinates}};
    for (const auto& [on, kind] : asked) {
        if (on) {
            passes.push_back(kind);
        }
    }
    return passes;
}

ModelFileSet modelFileSet(const BatchOptions& options) {
    return {viewCount(options.views), options.images, options.layout == OutputLayout::Objaverse,
            options.layout == OutputLayout::Gobjaverse, options.pointCloudPoints > 0};
}

fs::path cameraMatrixPath(const fs::path& folder, std::size_t index) {
    return folder / (viewStem(index) + ".npy");
}

fs::path cameraFilePath(const fs::path& folder, std::size_t index) {
    return folder / (viewStem(index) + ".json");
}

std::vector<fs::path> modelFiles(const fs::path& folder, const ModelFileSet& set) {
    std::vector<fs::path> files;
    for (std::uint32_t view = 0; view < set.views; ++view) {
        files.push_back(viewImagePath(folder, view));
        for (ViewImage kind : extraPasses(set.extras)) {
            files.push_back(viewImagePath(folder, view, kind, set.extras));
        }
        if (set.cameraMatrices) {
            files.push_back(cameraMatrixPath(folder, view));
        }
        if (set.cameraFiles) {
            files.push_back(cameraFilePath(folder, view));
        }
    }
    if (set.pointCloud) {
        files.push_back(folder / kPointCloudFileName);
    }
    files.push_back(folder / kMetadataFileName);
    files.push_back(folder / kTransformsFileName);
    return files;
}

bool modelFinished(const fs::path& folder, const ModelFileSet& set) {
    std::error_code ec;
    for (const fs::path& file : modelFiles(folder, set)) {
        if (!fs::is_regular_file(file, ec)) {
            return false;
        }
    }
    return true;
}

void removePartialFiles(const fs::path& folder) {
    std::error_code ec;
    std::vector<fs::path> partial;
    for (auto it = fs::directory_iterator(folder, ec); !ec && it != fs::directory_iterator();
         it.increment(ec)) {
        if (it->path().extension() == ".part") {
            partial.push_back(it->path());
        }
    }
    for (const fs::path& path : partial) {
        fs::remove(path, ec);
    }
}

}  // namespace encore::batch
