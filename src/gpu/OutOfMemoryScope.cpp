#include "encore/gpu/OutOfMemoryScope.h"

#include <string>

namespace encore::gpu {

OutOfMemoryScope::OutOfMemoryScope(Context& context) : mContext(&context) {
    mContext->device().PushErrorScope(wgpu::ErrorFilter::OutOfMemory);
}

OutOfMemoryScope::~OutOfMemoryScope() {
    if (mOpen) {
        (void)finish("");
    }
}

Result<void> OutOfMemoryScope::finish(std::string_view what) {
    mOpen = false;
    bool outOfMemory = false;
    std::string message;
    const bool completed = mContext->wait(mContext->device().PopErrorScope(
        wgpu::CallbackMode::WaitAnyOnly,
        [&](wgpu::PopErrorScopeStatus status, wgpu::ErrorType type, wgpu::StringView text) {
            // A lost device ends the scope with an error status: the loss is reported by
            // Context::checkNoErrors, with its own code.
            if (status == wgpu::PopErrorScopeStatus::Success &&
                type == wgpu::ErrorType::OutOfMemory) {
                outOfMemory = true;
                message = std::string(std::string_view(text));
            }
        }));
    if (!completed || !outOfMemory) {
        return {};
    }
    // Dawn appends a source location on lines of its own; the first line is the message.
    if (const auto newline = message.find('\n'); newline != std::string::npos) {
        message.resize(newline);
    }
    return makeError(ErrorCode::OutOfMemory,
                     std::string(what) + ": the GPU ran out of memory (" + message + ").");
}

}  // namespace encore::gpu
