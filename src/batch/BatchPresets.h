#pragma once

// Dataset presets (--preset NAME, Python preset=): the options that make a batch render what a
// published 3D generation pipeline rendered for its training data, each value with the public
// source it comes from. A preset is only option values, as the command line writes them: they
// are applied as if given, and an option given explicitly replaces the preset's value of it (and
// drops the preset's options it excludes). What a pipeline did that no option does yet is said
// in `notHonoured`, never pretended.
//
// `encore batch --preset list` prints them (presetListing); docs/batch.md's preset table is
// presetsMarkdown's.

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace encore::batch {

struct PresetValue {
    std::string option;  // The command line's name, without dashes ("fov").
    std::string value;   // As the command line writes it ("true" for a flag).
    std::string source;  // Where the number comes from: a URL, and what in it.
};

struct BatchPreset {
    std::string name;
    std::string summary;
    std::vector<PresetValue> values;
    // What the pipeline renders that the preset does not (yet) reproduce; empty: nothing.
    std::string notHonoured;
};

std::span<const BatchPreset> batchPresets();

// The preset of that name; nullptr if none.
const BatchPreset* findPreset(std::string_view name);

// The presets' names, for help and errors.
std::vector<std::string> presetNames();

// What `encore batch --preset list` prints: each preset, its options and their sources.
std::string presetListing();

// docs/batch.md's table of presets (Markdown).
std::string presetsMarkdown();

}  // namespace encore::batch
