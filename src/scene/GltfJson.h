#pragma once

// Typed, non-throwing reads of glTF JSON fields. A FieldReader wraps one JSON object that stands
// for one glTF element ("accessor 3", "material 1 normalTexture") and keeps the first type error
// it meets, so a parser can read every field of an element in a row and check once at the end.
// Absent optional fields yield the glTF default; present fields of the wrong type are errors
// that name the element, the field and the offending value.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "encore/core/Result.h"

namespace encore::scene {

using Json = nlohmann::json;

// A short rendering of a JSON value for error messages (never throws, at most ~40 characters).
std::string describeJson(const Json& value);

// A number for messages as a person would write it ("0.5", not "0.500000").
std::string formatNumber(double value);

class FieldReader {
  public:
    // `element` names the object in messages; a non-object is an error right away.
    FieldReader(const Json& object, std::string element);

    const std::string& element() const { return mElement; }
    bool has(std::string_view key) const;

    // Unsigned integers (integral floating-point values such as 2.0 are accepted).
    std::optional<std::uint64_t> optionalUint(std::string_view key);
    std::uint64_t uint(std::string_view key, std::uint64_t fallback);
    std::uint64_t requiredUint(std::string_view key);
    // An index into a top-level array: an unsigned integer below 2^32 - 1.
    std::optional<std::uint32_t> optionalIndex(std::string_view key);
    std::uint32_t requiredIndex(std::string_view key);

    double number(std::string_view key, double fallback);
    bool boolean(std::string_view key, bool fallback);
    std::optional<std::string> optionalString(std::string_view key);
    std::string string(std::string_view key, std::string fallback = {});
    std::string requiredString(std::string_view key);

    // Arrays of numbers; absent yields an empty vector. `expectedSize` 0 accepts any length.
    std::vector<double> numbers(std::string_view key, std::size_t expectedSize = 0);
    std::vector<std::uint32_t> indices(std::string_view key);

    // Nested values; absent yields nullptr, a value of another type is an error.
    const Json* object(std::string_view key);
    const Json* array(std::string_view key);
    // An object, or nullptr when absent or of another type: for `extras`, which may hold any
    // value, of which only an object can carry what Encore reads.
    const Json* objectIfAny(std::string_view key) const;

    // Records an error unless one is already recorded.
    void fail(ErrorCode code, std::string message);
    bool failed() const { return mError.has_value(); }
    const Error& error() const { return *mError; }

  private:
    const Json* find(std::string_view key) const;
    void failType(std::string_view key, std::string_view expected, const Json& value);

    const Json* mObject = nullptr;
    std::string mElement;
    std::optional<Error> mError;
};

// Reads a non-negative integer from any JSON number (integral floats accepted).
std::optional<std::uint64_t> jsonToUint(const Json& value);

// Calls `read` with a FieldReader named "<elementName> <i>" for each element of the top-level
// array root[key] (absent: no calls) and stops at the first error the reader records.
Result<void> forEachElement(const Json& root,
                            std::string_view key,
                            std::string_view elementName,
                            const std::function<void(FieldReader&, std::size_t)>& read);

// The object extensions.<name> of the reader's element, or nullptr when absent.
const Json* extensionObject(FieldReader& reader, std::string_view name);

}  // namespace encore::scene
