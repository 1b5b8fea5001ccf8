#include <cstdio>

#include "Commands.h"

namespace encore::app {

int reportError(const Error& error) {
    std::fprintf(stderr, "error: %s\n", error.message.c_str());
    switch (error.code) {
        case ErrorCode::NoAdapter:
            return kExitNoAdapter;
        case ErrorCode::ValidationError:
        case ErrorCode::DeviceError:
            return kExitGpuError;
        case ErrorCode::InvalidArgument:
            return kExitUsage;
        default:
            return kExitFailure;
    }
}

}  // namespace encore::app
