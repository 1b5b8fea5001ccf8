#pragma once

// Errors as values. The library never throws across its API: every operation that can fail on
// input (files, glTF content, the GPU's availability) returns a Result. Messages are full
// sentences with the offending values in parentheses; callers add context on the way up with
// Error::withContext so the final message reads "Loading 'x.glb': accessor 3 ...".

#include <cassert>
#include <string>
#include <string_view>
#include <utility>
#include <variant>

namespace encore {

enum class ErrorCode {
    InvalidArgument,  // A caller passed something meaningless (a zero size, an unknown name).
    FileNotFound,     // A path that does not exist.
    FileUnreadable,   // Exists but cannot be read (permissions, a directory, I/O error).
    InvalidFormat,    // Malformed content: bad JSON, bad GLB framing, out-of-range data.
    Unsupported,      // Well-formed but uses something Encore does not implement.
    LimitExceeded,    // A size that would overflow or exceed a sane allocation limit.
    NoAdapter,        // No usable GPU adapter (e.g. only Dawn's Null backend).
    DeviceError,      // Device creation failed or the device was lost.
    ValidationError,  // WebGPU reported a validation error.
    OutOfMemory,      // The GPU could not allocate a resource (a WebGPU out-of-memory error).
    IoError,          // Writing an output failed.
    NoDisplay,        // No display to open a window on (encore view).
};

// A name for each code, for logs and test messages.
std::string_view errorCodeName(ErrorCode code);

struct Error {
    ErrorCode code;
    std::string message;

    // Returns a copy whose message is "<context>: <message>".
    Error withContext(std::string_view context) const;
};

template <typename T>
class [[nodiscard]] Result {
  public:
    Result(T value) : mState(std::move(value)) {}
    Result(Error error) : mState(std::move(error)) {}

    bool ok() const { return std::holds_alternative<T>(mState); }
    explicit operator bool() const { return ok(); }

    T& value() & {
        assert(ok());
        return std::get<T>(mState);
    }
    const T& value() const& {
        assert(ok());
        return std::get<T>(mState);
    }
    T&& value() && {
        assert(ok());
        return std::get<T>(std::move(mState));
    }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }
    T& operator*() & { return value(); }
    const T& operator*() const& { return value(); }

    const Error& error() const {
        assert(!ok());
        return std::get<Error>(mState);
    }

  private:
    std::variant<T, Error> mState;
};

template <>
class [[nodiscard]] Result<void> {
  public:
    Result() = default;
    Result(Error error) : mError(std::move(error)), mOk(false) {}

    bool ok() const { return mOk; }
    explicit operator bool() const { return ok(); }
    const Error& error() const {
        assert(!ok());
        return mError;
    }

  private:
    Error mError{ErrorCode::InvalidArgument, {}};
    bool mOk = true;
};

inline Error makeError(ErrorCode code, std::string message) {
    return Error{code, std::move(message)};
}

namespace detail {
// Prints where and which invariant broke, then aborts (ENCORE_CHECK).
[[noreturn]] void checkFailed(const char* condition,
                              const char* file,
                              int line,
                              std::string_view message);
}  // namespace detail

}  // namespace encore

// Propagates the error of a Result-returning expression, otherwise yields nothing.
#define ENCORE_TRY(expression)               \
    do {                                     \
        auto encoreTryResult = (expression); \
        if (!encoreTryResult.ok()) {         \
            return encoreTryResult.error();  \
        }                                    \
    } while (false)

// Assigns the value of a Result-returning expression to `target`, or returns its error.
// `target` may declare a variable: ENCORE_TRY_ASSIGN(auto image, decode(bytes)). Expands to
// several statements, so it stands in a block of its own, never as an unbraced if's body.
#define ENCORE_TRY_ASSIGN(target, expression) \
    ENCORE_TRY_ASSIGN_IMPL(ENCORE_TRY_CONCAT(encoreTryAssign, __LINE__), target, expression)
#define ENCORE_TRY_ASSIGN_IMPL(result, target, expression) \
    auto result = (expression);                            \
    if (!result.ok()) {                                    \
        return result.error();                             \
    }                                                      \
    target = std::move(result).value()
#define ENCORE_TRY_CONCAT(a, b) ENCORE_TRY_CONCAT_IMPL(a, b)
#define ENCORE_TRY_CONCAT_IMPL(a, b) a##b

// A programmer's error, never bad input (that is a Result): when `condition` is false, prints it
// with `message` (evaluated only then) and the file and line, and aborts.
#define ENCORE_CHECK(condition, message)                                              \
    do {                                                                              \
        if (!(condition)) {                                                           \
            ::encore::detail::checkFailed(#condition, __FILE__, __LINE__, (message)); \
        }                                                                             \
    } while (false)
