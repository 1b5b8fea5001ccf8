#include "batch/FailureLog.h"

#include <cerrno>
#include <cstring>

#include <nlohmann/json.hpp>

namespace encore::batch {

struct FailureLog::State {
    mutable std::mutex mutex;
    std::FILE* file = nullptr;  // Null for a log in memory.
    std::vector<Failure> entries;
    ~State() {
        if (file) {
            std::fclose(file);
        }
    }
};

Result<FailureLog> FailureLog::create(const std::filesystem::path& path) {
    FailureLog log;
    log.mState = std::make_shared<State>();
    log.mState->file = std::fopen(path.c_str(), "w");
    if (!log.mState->file) {
        return makeError(ErrorCode::IoError,
                         "Cannot create '" + path.string() + "' (" + std::strerror(errno) + ").");
    }
    return log;
}

FailureLog FailureLog::inMemory() {
    FailureLog log;
    log.mState = std::make_shared<State>();
    return log;
}

void FailureLog::record(const std::filesystem::path& file,
                        const std::string& stage,
                        const std::string& message) {
    nlohmann::json line = {{"file", file.string()}, {"stage", stage}, {"error", message}};
    // Replacement of invalid UTF-8 (file names, messages quoting file contents) rather than an
    // exception.
    const std::string text =
        line.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
    std::lock_guard lock(mState->mutex);
    if (mState->file) {
        std::fwrite(text.data(), 1, text.size(), mState->file);
        std::fflush(mState->file);
    }
    mState->entries.push_back({file, stage, message});
}

std::size_t FailureLog::count() const {
    std::lock_guard lock(mState->mutex);
    return mState->entries.size();
}

std::vector<Failure> FailureLog::entries() const {
    std::lock_guard lock(mState->mutex);
    return mState->entries;
}

}  // namespace encore::batch
