#pragma once

// OutOfMemoryScope turns an out-of-memory error of the GPU objects created while it is open into
// an error value: Dawn reports such errors through error scopes (PushErrorScope(OutOfMemory))
// rather than through the call that allocated. finish() pops the scope, waits for its result and
// returns ErrorCode::OutOfMemory naming what was being created. Validation errors pass through
// to the context's uncaptured-error log as before.
//
// Scopes nest per device. A scope that is never finished is popped, its result ignored, when it
// is destroyed (an early return on another error).

#include <string_view>

#include "encore/core/Result.h"
#include "encore/gpu/Context.h"

namespace encore::gpu {

// ErrorCode::OutOfMemory reading "<what>: the GPU ran out of memory (<reason>)." from Dawn's
// message, of which only the first line is kept (Dawn appends its source location on lines of
// their own).
Error outOfMemoryError(std::string_view what, std::string_view dawnMessage);

class OutOfMemoryScope {
  public:
    explicit OutOfMemoryScope(Context& context);
    ~OutOfMemoryScope();
    OutOfMemoryScope(const OutOfMemoryScope&) = delete;
    OutOfMemoryScope& operator=(const OutOfMemoryScope&) = delete;

    // Pops the scope. `what` names the work, e.g. "Preparing 'x.glb' for strategy bundles".
    Result<void> finish(std::string_view what);

  private:
    Context* mContext;
    bool mOpen = true;
};

}  // namespace encore::gpu
