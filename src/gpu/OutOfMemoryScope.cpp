#include "gpu/OutOfMemoryScope.h"

#include <string>

namespace encore::gpu {

Error outOfMemoryError(std::string_view what, std::string_view dawnMessage) {
    const std::string_view reason = dawnMessage.substr(0, dawnMessage.find('\n'));
    return makeError(ErrorCode::OutOfMemory, std::string(what) + ": the GPU ran out of memory (" +
                                                 std::string(reason) + ").");
}

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
    return outOfMemoryError(what, message);
}

}  // namespace encore::gpu
