#include "encore/batch/BatchInputs.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <set>
#include <sstream>
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/FileIO.h"

namespace encore::batch {
namespace {

namespace fs = std::filesystem;

std::string lowercase(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return text;
}

std::string quoted(const fs::path& path) {
    return "'" + path.string() + "'";
}

std::string trim(std::string_view text) {
    const auto first = text.find_first_not_of(" \t\r\n");
    if (first == std::string_view::npos) {
        return {};
    }
    const auto last = text.find_last_not_of(" \t\r\n");
    return std::string(text.substr(first, last - first + 1));
}

// The deepest folder holding every path (all absolute and lexically normal).
fs::path commonFolder(std::span<const fs::path> paths) {
    fs::path common = paths.front().parent_path();
    for (const fs::path& path : paths.subspan(1)) {
        const fs::path folder = path.parent_path();
        auto [mine, theirs] =
            std::mismatch(common.begin(), common.end(), folder.begin(), folder.end());
        fs::path prefix;
        for (auto part = common.begin(); part != mine; ++part) {
            prefix /= *part;
        }
        common = prefix;
    }
    return common;
}

Result<std::vector<fs::path>> readList(const fs::path& list) {
    ENCORE_TRY_ASSIGN(auto bytes, readFile(list));
    const std::string text(bytes.begin(), bytes.end());
    std::vector<std::string> entries;
    if (lowercase(list.extension().string()) == ".json") {
        const nlohmann::json json = nlohmann::json::parse(text, nullptr, false);
        if (json.is_discarded() || !json.is_array()) {
            return makeError(ErrorCode::InvalidFormat,
                             "The input list " + quoted(list) + " is not a JSON array of paths.");
        }
        for (const nlohmann::json& entry : json) {
            if (!entry.is_string()) {
                return makeError(ErrorCode::InvalidFormat, "The input list " + quoted(list) +
                                                               " holds a value that is not "
                                                               "a path (" +
                                                               entry.dump() + ").");
            }
            entries.push_back(entry.get<std::string>());
        }
    } else {
        if (text.find('\0') != std::string::npos) {
            return makeError(ErrorCode::InvalidFormat,
                             "The input " + quoted(list) +
                                 " is neither a model, a folder, nor a list of paths (it holds "
                                 "binary data).");
        }
        std::istringstream lines(text);
        for (std::string line; std::getline(lines, line);) {
            if (std::string entry = trim(line); !entry.empty() && entry[0] != '#') {
                entries.push_back(std::move(entry));
            }
        }
    }
    const fs::path base = fs::absolute(list).parent_path();
    std::vector<fs::path> paths;
    for (const std::string& entry : entries) {
        paths.push_back(base / fs::path(entry));
    }
    return paths;
}

// Each path once, absolute and lexically normal, in list order.
std::vector<fs::path> uniqueAbsolutePaths(std::span<const fs::path> listed) {
    std::vector<fs::path> paths;
    std::set<fs::path> seen;
    for (const fs::path& entry : listed) {
        const fs::path path = fs::absolute(entry).lexically_normal();
        if (seen.insert(path).second) {
            paths.push_back(path);
        }
    }
    return paths;
}

std::vector<BatchInput> namedInputs(const std::vector<fs::path>& paths, const fs::path& root) {
    const std::vector<std::string> names = outputNames(paths, root);
    std::vector<BatchInput> inputs;
    for (std::size_t i = 0; i < paths.size(); ++i) {
        inputs.push_back({paths[i], names[i]});
    }
    return inputs;
}

std::vector<fs::path> searchFolder(const fs::path& folder) {
    std::vector<fs::path> paths;
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(
             folder, fs::directory_options::skip_permission_denied, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
        if (it->is_regular_file(ec) && isModelPath(it->path())) {
            paths.push_back(it->path().lexically_normal());
        }
    }
    return paths;
}

}  // namespace

bool isModelPath(const fs::path& path) {
    const std::string extension = lowercase(path.extension().string());
    return extension == ".gltf" || extension == ".glb";
}

std::vector<std::string> outputNames(std::span<const fs::path> paths, const fs::path& root) {
    std::vector<std::string> names;
    std::map<std::string, int> uses;
    for (const fs::path& path : paths) {
        fs::path relative = path.lexically_relative(root);
        if (relative.empty() || *relative.begin() == "..") {
            relative = path.filename();  // Outside the root: the caller broke the contract.
        }
        names.push_back(relative.replace_extension().generic_string());
        ++uses[names.back()];
    }
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (uses[names[i]] > 1) {
            names[i] += paths[i].extension().string();
        }
    }
    return names;
}

std::vector<std::string> variantSampleNames(const std::string& name,
                                            std::span<const std::string> variants) {
    std::vector<std::string> safe;
    std::map<std::string, int> uses;
    for (const std::string& variant : variants) {
        std::string folder = variant;
        for (char& c : folder) {
            const unsigned char u = static_cast<unsigned char>(c);
            if (!std::isalnum(u) || u >= 0x80) {
                c = (c == '.' || c == '-' || c == '_') ? c : '_';
            }
        }
        safe.push_back(folder.empty() ? "variant" : folder);
        ++uses[safe.back()];
    }
    std::vector<std::string> names;
    std::set<std::string> taken;
    for (std::size_t v = 0; v < safe.size(); ++v) {
        std::string sample = name + "@" + safe[v];
        // Shared names get the index; so does one that an appended index made ("a-1" beside
        // two variants named "a").
        if (uses[safe[v]] > 1 || taken.contains(sample)) {
            do {
                sample += "-" + std::to_string(v);
            } while (taken.contains(sample));
        }
        taken.insert(sample);
        names.push_back(std::move(sample));
    }
    return names;
}

Result<std::vector<BatchInput>> discoverInputs(const fs::path& input) {
    std::error_code ec;
    const auto status = fs::status(input, ec);
    if (ec || !fs::exists(status)) {
        return makeError(ErrorCode::FileNotFound,
                         "The input " + quoted(input) + " does not exist.");
    }
    const fs::path absolute = fs::absolute(input).lexically_normal();
    std::vector<fs::path> paths;
    fs::path root;
    if (fs::is_directory(status)) {
        paths = searchFolder(absolute);
        std::sort(paths.begin(), paths.end());
        root = absolute;
        if (paths.empty()) {
            return makeError(ErrorCode::InvalidArgument,
                             "The folder " + quoted(input) + " holds no .gltf or .glb file.");
        }
    } else if (isModelPath(absolute)) {
        paths.push_back(absolute);
        root = absolute.parent_path();
    } else {
        ENCORE_TRY_ASSIGN(auto listed, readList(absolute));
        if (listed.empty()) {
            return makeError(ErrorCode::InvalidArgument,
                             "The input list " + quoted(input) + " names no model.");
        }
        return listedInputs(listed);
    }
    return namedInputs(paths, root);
}

Result<std::vector<BatchInput>> listedInputs(std::span<const fs::path> listed) {
    if (listed.empty()) {
        return makeError(ErrorCode::InvalidArgument, "The list of models is empty.");
    }
    const std::vector<fs::path> paths = uniqueAbsolutePaths(listed);
    return namedInputs(paths, commonFolder(paths));
}

}  // namespace encore::batch
