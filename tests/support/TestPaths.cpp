#include "TestPaths.h"

#include <unistd.h>

namespace encore::test {

std::optional<std::filesystem::path> sharedModelsDir() {
    std::filesystem::path dir = ENCORE_SHARED_MODELS_DIR;
    if (const char* overridden = std::getenv("ENCORE_MODELS_DIR")) {
        dir = overridden;
    }
    std::error_code ec;
    if (std::filesystem::is_regular_file(dir / "index.json", ec)) {
        return dir;
    }
    return std::nullopt;
}

std::optional<std::filesystem::path> sharedReferenceDir() {
    std::filesystem::path dir =
        std::filesystem::path(ENCORE_SHARED_MODELS_DIR) / ".." / "reference";
    if (const char* overridden = std::getenv("ENCORE_REFERENCE_DIR")) {
        dir = overridden;
    }
    std::error_code ec;
    if (std::filesystem::is_regular_file(dir / "list.txt", ec)) {
        return dir.lexically_normal();
    }
    return std::nullopt;
}

std::filesystem::path sourceDir() {
    return ENCORE_SOURCE_DIR;
}

std::filesystem::path makeTempDir(const std::string& name) {
    auto dir = std::filesystem::temp_directory_path() /
               ("encore-test-" + std::to_string(::getpid()) + "-" + name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace encore::test
