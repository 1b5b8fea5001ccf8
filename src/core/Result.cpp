#include "encore/core/Result.h"

#include <cstdio>
#include <cstdlib>

namespace encore {

std::string_view errorCodeName(ErrorCode code) {
    switch (code) {
        case ErrorCode::InvalidArgument:
            return "invalid argument";
        case ErrorCode::FileNotFound:
            return "file not found";
        case ErrorCode::FileUnreadable:
            return "file unreadable";
        case ErrorCode::InvalidFormat:
            return "invalid format";
        case ErrorCode::Unsupported:
            return "unsupported";
        case ErrorCode::LimitExceeded:
            return "limit exceeded";
        case ErrorCode::NoAdapter:
            return "no adapter";
        case ErrorCode::DeviceError:
            return "device error";
        case ErrorCode::ValidationError:
            return "validation error";
        case ErrorCode::OutOfMemory:
            return "out of GPU memory";
        case ErrorCode::IoError:
            return "I/O error";
        case ErrorCode::NoDisplay:
            return "no display";
    }
    return "unknown error";
}

Error Error::withContext(std::string_view context) const {
    std::string combined(context);
    combined += ": ";
    combined += message;
    return Error{code, std::move(combined)};
}

namespace detail {

void checkFailed(const char* condition, const char* file, int line, std::string_view message) {
    std::fprintf(stderr, "encore: internal error at %s:%d: %.*s (%s is false)\n", file, line,
                 int(message.size()), message.data(), condition);
    std::abort();
}

}  // namespace detail

}  // namespace encore
