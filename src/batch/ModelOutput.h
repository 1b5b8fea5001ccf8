#pragma once

// The files of one model in a batch's output folder, and whether all of them are in place.
//
// OUT/<name>/000.png ... (one per view, with their normal and depth images and, in the Objaverse
// layout, 000.npy camera matrices), then OUT/<name>/metadata.json and OUT/<name>/transforms.json,
// each written under a temporary name, flushed and renamed (the images and matrices together
// once the last image is written: encore::writePartialFile and commitFiles), metadata.json and
// transforms.json last, in that order (encore::writeFileAtomically): a model is finished exactly
// when every one of its files exists, and a batch run again skips it. Output of a version that
// wrote no metadata.json is rendered again.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "encore/batch/Batch.h"
#include "encore/batch/ViewImages.h"

namespace encore::batch {

inline constexpr const char* kTransformsFileName = "transforms.json";

// What a finished model's folder holds.
struct ModelFileSet {
    std::uint32_t views = 0;
    ExtraImages extras;
    bool cameraMatrices = false;  // 000.npy ... (OutputLayout::Objaverse).
    bool cameraFiles = false;     // 000.json ... (OutputLayout::Gobjaverse).
    bool pointCloud = false;      // points.ply (BatchOptions::pointCloudPoints).
};

ModelFileSet modelFileSet(const BatchOptions& options);

std::filesystem::path modelFolder(const std::filesystem::path& output, const std::string& name);

// The image of view `index` in `folder`: "000.png", "000_normal.png", "000_depth.png" (or
// .exr, as `extras` says), ...
std::filesystem::path viewImagePath(const std::filesystem::path& folder,
                                    std::size_t index,
                                    ViewImage kind = ViewImage::Color,
                                    const ExtraImages& extras = {});

// The passes `extras` asks for, in the order a view's images are listed.
std::vector<ViewImage> extraPasses(const ExtraImages& extras);

// View `index`'s camera matrix in `folder`: "000.npy", ...
std::filesystem::path cameraMatrixPath(const std::filesystem::path& folder, std::size_t index);

// View `index`'s camera file in `folder`: "000.json", ...
std::filesystem::path cameraFilePath(const std::filesystem::path& folder, std::size_t index);

// Every file a finished model has: per view its images (and camera file), then metadata.json
// and transforms.json.
std::vector<std::filesystem::path> modelFiles(const std::filesystem::path& folder,
                                              const ModelFileSet& files);

bool modelFinished(const std::filesystem::path& folder, const ModelFileSet& files);

// Removes what a stopped run left in `folder` (files ending in ".part"); keeps everything else.
void removePartialFiles(const std::filesystem::path& folder);

}  // namespace encore::batch
