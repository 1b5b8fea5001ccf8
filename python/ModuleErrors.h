#pragma once

// The Python module's exceptions: encore.Error and encore.LoadError (registered by
// EncoreModule.cpp), raised from the library's error values.

#include <stdexcept>
#include <utility>

#include "encore/core/Result.h"

namespace encore::python {

// Raised as encore.Error (GPU, I/O, arguments) and encore.LoadError (a model that does not
// load), each with the message `encore render` would print.
struct EncoreError : std::runtime_error {
    using std::runtime_error::runtime_error;
};
struct LoadError : EncoreError {
    using EncoreError::EncoreError;
};

template <typename T>
T valueOrThrow(Result<T> result) {
    if (!result) {
        throw EncoreError(result.error().message);
    }
    return std::move(*result);
}

}  // namespace encore::python
