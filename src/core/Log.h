#pragma once

// The library reports warnings and diagnostics through one process-wide sink. Only
// applications print: the default sink drops everything, and apps/encore installs one that
// writes "warning: ..." to stderr. Tests install a capturing sink.

#include <functional>
#include <string_view>

namespace encore {

enum class LogLevel { Debug, Info, Warning, Error };

using LogSink = std::function<void(LogLevel, std::string_view)>;

// Replaces the sink; returns the previous one so a scope can restore it.
LogSink setLogSink(LogSink sink);

void log(LogLevel level, std::string_view message);
inline void logWarning(std::string_view message) {
    log(LogLevel::Warning, message);
}
inline void logInfo(std::string_view message) {
    log(LogLevel::Info, message);
}
inline void logDebug(std::string_view message) {
    log(LogLevel::Debug, message);
}

}  // namespace encore
