#pragma once

// The models of a batch and the names their outputs get.
//
// An input is a directory (searched recursively for .gltf and .glb files, any letter case), a
// single .gltf/.glb file, a text file with one path per line, or a JSON file holding a list of
// paths (the form the Objaverse download scripts produce). Relative paths in a list resolve
// against the list's folder. Each model's output name is its path relative to the input root
// without the extension ("cars/red/model"): the searched directory, or the deepest folder that
// holds every listed file. Two files that differ only by their extension ("a.gltf", "a.glb")
// keep it in their names ("a.gltf", "a.glb"), so no two models share an output folder.
//
// A model drawn in a KHR_materials_variants variant is a sample of its own, named
// "<name>@<variant>" (variantSampleNames).

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "encore/core/Result.h"

namespace encore::batch {

struct BatchInput {
    std::filesystem::path path;  // As found or listed (list entries made absolute).
    std::string name;            // Relative output name, '/'-separated, never empty.
};

// Whether `path` names a glTF model by its extension (.gltf or .glb, any letter case).
bool isModelPath(const std::filesystem::path& path);

// The models `input` names, sorted by name for directories and in list order for lists (each
// path once). Fails with FileNotFound for a missing input, InvalidFormat for a list that is not
// one path per line or a JSON array of strings, and InvalidArgument when no model is found.
// Listed files are not opened: a missing one fails later, as that model's load.
Result<std::vector<BatchInput>> discoverInputs(const std::filesystem::path& input);

// The models of a list of paths (relative ones against the working folder), each once, in list
// order, named relative to the deepest folder that holds them all, as a list file's are. Fails
// with InvalidArgument for an empty list; the files are not opened.
Result<std::vector<BatchInput>> listedInputs(std::span<const std::filesystem::path> paths);

// Names for `paths` relative to `root`, as described above (paths must lie inside `root`).
std::vector<std::string> outputNames(std::span<const std::filesystem::path> paths,
                                     const std::filesystem::path& root);

// The output names of a model's samples in each of its material variants, by variant index:
// "<name>@<variant>", the variant's name kept to letters, digits, '.', '-' and '_' (every other
// character, '/' and spaces included, becomes '_'; an empty name becomes "variant"), and
// "-<index>" appended where two variants of the model would otherwise share a name
// ("shoe@midnight", "shoe@beach_ball", "shoe@red-2").
std::vector<std::string> variantSampleNames(const std::string& name,
                                            std::span<const std::string> variants);

}  // namespace encore::batch
