#pragma once

// The files of one model in a batch's output folder, and whether all of them are in place.
//
// OUT/<name>/000.png ... (one per view) and OUT/<name>/transforms.json, each written under a
// temporary name and renamed (encore::writeFileAtomically), transforms.json last: a model is
// finished exactly when every one of its files exists, and a batch run again skips it.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace encore::batch {

inline constexpr const char* kTransformsFileName = "transforms.json";

std::filesystem::path modelFolder(const std::filesystem::path& output, const std::string& name);

// What a view's image shows.
enum class ViewImage {
    Color,   // "000.png": the shaded picture, RGBA.
    Normal,  // "000_normal.png": world-space normals mapped to 0..255 (n * 0.5 + 0.5), alpha.
};

// The image of view `index` in `folder`: "000.png", "000_normal.png", ...
std::filesystem::path viewImagePath(const std::filesystem::path& folder,
                                    std::size_t index,
                                    ViewImage kind = ViewImage::Color);

// Every file a finished model has: its `views` images (and their normal images with
// `normals`), then transforms.json.
std::vector<std::filesystem::path> modelFiles(const std::filesystem::path& folder,
                                              std::uint32_t views,
                                              bool normals = false);

bool modelFinished(const std::filesystem::path& folder, std::uint32_t views, bool normals = false);

// Removes what a stopped run left in `folder` (files ending in ".part"); keeps everything else.
void removePartialFiles(const std::filesystem::path& folder);

}  // namespace encore::batch
