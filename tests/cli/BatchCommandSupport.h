#pragma once

// What the tests of `encore batch` share: generated collections, the command line, and reading
// what it wrote.

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "GltfBuilder.h"
#include "TestFiles.h"  // readBytes

namespace encore::test {

// `count` generated scenes in sub-folders (the first two named set0/model.glb and
// set1/model.glb, the others more/sceneN.glb) and a malformed broken.gltf.
std::filesystem::path makeCollection(const std::string& name, int count, int objects);

// The files under `dir` (recursively) whose extension is `extension` (".png").
std::vector<std::filesystem::path> filesUnder(const std::filesystem::path& dir,
                                              const std::string& extension);

// One JSON value per line (failures.jsonl).
std::vector<nlohmann::json> jsonLines(const std::filesystem::path& path);

// A square of two triangles facing +Z, its base colour from the image at `imageUri`.
GltfBuilder texturedQuad(const std::string& imageUri);

// "-v batch INPUT -o OUTPUT EXTRA", quoted.
std::string batchArguments(const std::filesystem::path& input,
                           const std::filesystem::path& output,
                           const std::string& extra);

// Runs `encore batch` on `input` once per case, with `common` and the case's options (first):
// each must be a usage error (exit 2) whose message contains the case's text (second), and no
// run may write an image.
void expectUsageErrors(const std::filesystem::path& input,
                       const std::filesystem::path& output,
                       const std::string& common,
                       const std::vector<std::pair<std::string, std::string>>& cases);

}  // namespace encore::test
