#pragma once

// The files of one model in a batch's output folder, and whether all of them are in place.
//
// OUT/<name>/000.png ... (one per view) and OUT/<name>/transforms.json, each written under a
// temporary name, flushed and renamed (the images together once the last is written:
// encore::writePartialFile and commitFiles), transforms.json last (encore::writeFileAtomically):
// a model is finished exactly when every one of its files exists, and a batch run again skips it.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "encore/batch/ViewImages.h"

namespace encore::batch {

inline constexpr const char* kTransformsFileName = "transforms.json";

std::filesystem::path modelFolder(const std::filesystem::path& output, const std::string& name);

// The image of view `index` in `folder`: "000.png", "000_normal.png", "000_depth.png", ...
std::filesystem::path viewImagePath(const std::filesystem::path& folder,
                                    std::size_t index,
                                    ViewImage kind = ViewImage::Color);

// Every file a finished model has: its `views` images and their `extras`, then transforms.json.
std::vector<std::filesystem::path> modelFiles(const std::filesystem::path& folder,
                                              std::uint32_t views,
                                              const ExtraImages& extras = {});

bool modelFinished(const std::filesystem::path& folder,
                   std::uint32_t views,
                   const ExtraImages& extras = {});

// Removes what a stopped run left in `folder` (files ending in ".part"); keeps everything else.
void removePartialFiles(const std::filesystem::path& folder);

}  // namespace encore::batch
