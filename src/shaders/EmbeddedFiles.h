#pragma once

#include <span>
#include <string_view>

namespace encore::shaders {

// A file compiled into the binary by cmake/EmbedFiles.cmake.
struct EmbeddedFile {
    std::string_view name;
    std::string_view contents;
};

// The .wgsl files of src/shaders, by file name.
std::span<const EmbeddedFile> wgslFiles();

}  // namespace encore::shaders
