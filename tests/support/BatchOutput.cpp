#include "BatchOutput.h"

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

namespace encore::test {

namespace fs = std::filesystem;

std::string metadataWithoutTimings(const std::string& text) {
    nlohmann::json json = nlohmann::json::parse(text, nullptr, false);
    if (json.is_discarded() || !json.is_object()) {
        return text;  // Compared as it is: a broken file differs from a good one.
    }
    json.erase("seconds");
    json.erase("gpu");
    return json.dump(2);
}

std::map<std::string, std::string> batchOutputFiles(const fs::path& folder) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(folder)) {
        if (!entry.is_regular_file() || entry.path().filename() == "failures.jsonl") {
            continue;
        }
        std::ifstream file(entry.path(), std::ios::binary);
        std::stringstream bytes;
        bytes << file.rdbuf();
        std::string contents = bytes.str();
        if (entry.path().filename() == "metadata.json") {
            contents = metadataWithoutTimings(contents);
        }
        files[fs::relative(entry.path(), folder).generic_string()] = std::move(contents);
    }
    return files;
}

}  // namespace encore::test
