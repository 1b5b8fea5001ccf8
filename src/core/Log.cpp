#include "core/Log.h"

#include <mutex>
#include <utility>

namespace encore {
namespace {

std::mutex& sinkMutex() {
    static std::mutex mutex;
    return mutex;
}

LogSink& currentSink() {
    static LogSink sink;
    return sink;
}

}  // namespace

LogSink setLogSink(LogSink sink) {
    std::lock_guard lock(sinkMutex());
    return std::exchange(currentSink(), std::move(sink));
}

void log(LogLevel level, std::string_view message) {
    // Dawn calls back from its own threads (device loss, errors), hence the lock.
    std::lock_guard lock(sinkMutex());
    if (currentSink()) {
        currentSink()(level, message);
    }
}

}  // namespace encore
