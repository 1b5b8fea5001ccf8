#include "TestFiles.h"

#include <fstream>
#include <sstream>

namespace encore::test {

std::string readBytes(const std::filesystem::path& path) {
    std::ifstream file(path, std::ios::binary);
    std::stringstream bytes;
    bytes << file.rdbuf();
    return bytes.str();
}

std::map<std::string, std::string> filesUnder(const std::filesystem::path& folder) {
    std::map<std::string, std::string> files;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(folder)) {
        if (entry.is_regular_file() && entry.path().filename() != "failures.jsonl") {
            files[std::filesystem::relative(entry.path(), folder).generic_string()] =
                readBytes(entry.path());
        }
    }
    return files;
}

}  // namespace encore::test
