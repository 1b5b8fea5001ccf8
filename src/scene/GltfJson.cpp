#include "scene/GltfJson.h"

#include <cmath>
#include <cstdio>
#include <limits>

namespace encore::scene {

std::string describeJson(const Json& value) {
    // error_handler_t::replace: a string with invalid UTF-8 must not make the message throw.
    std::string text = value.dump(-1, ' ', false, Json::error_handler_t::replace);
    constexpr std::size_t kMaxLength = 40;
    if (text.size() > kMaxLength) {
        text = text.substr(0, kMaxLength - 3) + "...";
    }
    return text;
}

std::string formatNumber(double value) {
    char text[32];
    std::snprintf(text, sizeof(text), "%g", value);
    return text;
}

std::optional<std::uint64_t> jsonToUint(const Json& value) {
    if (value.is_number_unsigned()) {
        return value.get<std::uint64_t>();
    }
    if (value.is_number_integer()) {
        const auto signedValue = value.get<std::int64_t>();
        if (signedValue < 0) {
            return std::nullopt;
        }
        return static_cast<std::uint64_t>(signedValue);
    }
    if (value.is_number_float()) {
        const double number = value.get<double>();
        // 2^64 is the first double past the uint64 range.
        if (std::isfinite(number) && number >= 0.0 && number < 18446744073709551616.0 &&
            std::floor(number) == number) {
            return static_cast<std::uint64_t>(number);
        }
    }
    return std::nullopt;
}

FieldReader::FieldReader(const Json& object, std::string element)
    : mObject(&object), mElement(std::move(element)) {
    if (!object.is_object()) {
        fail(ErrorCode::InvalidFormat,
             mElement + " is not a JSON object (got " + describeJson(object) + ").");
    }
}

const Json* FieldReader::find(std::string_view key) const {
    if (!mObject->is_object()) {
        return nullptr;
    }
    const auto it = mObject->find(key);
    return it == mObject->end() ? nullptr : &*it;
}

bool FieldReader::has(std::string_view key) const {
    return find(key) != nullptr;
}

void FieldReader::fail(ErrorCode code, std::string message) {
    if (!mError) {
        mError = Error{code, std::move(message)};
    }
}

void FieldReader::failType(std::string_view key, std::string_view expected, const Json& value) {
    fail(ErrorCode::InvalidFormat, mElement + " has an invalid '" + std::string(key) +
                                       "' (expected " + std::string(expected) + ", got " +
                                       describeJson(value) + ").");
}

std::optional<std::uint64_t> FieldReader::optionalUint(std::string_view key) {
    const Json* value = find(key);
    if (!value) {
        return std::nullopt;
    }
    auto number = jsonToUint(*value);
    if (!number) {
        failType(key, "a non-negative integer", *value);
    }
    return number;
}

std::uint64_t FieldReader::uint(std::string_view key, std::uint64_t fallback) {
    return optionalUint(key).value_or(fallback);
}

std::uint64_t FieldReader::requiredUint(std::string_view key) {
    if (!find(key)) {
        fail(ErrorCode::InvalidFormat,
             mElement + " lacks the required '" + std::string(key) + "' property.");
        return 0;
    }
    return uint(key, 0);
}

std::optional<std::uint32_t> FieldReader::optionalIndex(std::string_view key) {
    const auto value = optionalUint(key);
    if (!value) {
        return std::nullopt;
    }
    if (*value >= std::numeric_limits<std::uint32_t>::max()) {
        fail(ErrorCode::InvalidFormat, mElement + " has an out-of-range '" + std::string(key) +
                                           "' index (" + std::to_string(*value) + ").");
        return std::nullopt;
    }
    return static_cast<std::uint32_t>(*value);
}

std::uint32_t FieldReader::requiredIndex(std::string_view key) {
    if (!find(key)) {
        fail(ErrorCode::InvalidFormat,
             mElement + " lacks the required '" + std::string(key) + "' property.");
        return 0;
    }
    return optionalIndex(key).value_or(0);
}

double FieldReader::number(std::string_view key, double fallback) {
    const Json* value = find(key);
    if (!value) {
        return fallback;
    }
    if (!value->is_number()) {
        failType(key, "a number", *value);
        return fallback;
    }
    const double number = value->get<double>();
    if (!std::isfinite(number)) {
        failType(key, "a finite number", *value);
        return fallback;
    }
    return number;
}

bool FieldReader::boolean(std::string_view key, bool fallback) {
    const Json* value = find(key);
    if (!value) {
        return fallback;
    }
    if (!value->is_boolean()) {
        failType(key, "true or false", *value);
        return fallback;
    }
    return value->get<bool>();
}

std::optional<std::string> FieldReader::optionalString(std::string_view key) {
    const Json* value = find(key);
    if (!value) {
        return std::nullopt;
    }
    if (!value->is_string()) {
        failType(key, "a string", *value);
        return std::nullopt;
    }
    return value->get<std::string>();
}

std::string FieldReader::string(std::string_view key, std::string fallback) {
    return optionalString(key).value_or(std::move(fallback));
}

std::string FieldReader::requiredString(std::string_view key) {
    if (!find(key)) {
        fail(ErrorCode::InvalidFormat,
             mElement + " lacks the required '" + std::string(key) + "' property.");
        return {};
    }
    return string(key);
}

std::vector<double> FieldReader::numbers(std::string_view key, std::size_t expectedSize) {
    const Json* value = find(key);
    if (!value) {
        return {};
    }
    const std::string expected = expectedSize
                                     ? "an array of " + std::to_string(expectedSize) + " numbers"
                                     : std::string("an array of numbers");
    if (!value->is_array() || (expectedSize != 0 && value->size() != expectedSize)) {
        failType(key, expected, *value);
        return {};
    }
    std::vector<double> result;
    result.reserve(value->size());
    for (const Json& item : *value) {
        if (!item.is_number() || !std::isfinite(item.get<double>())) {
            failType(key, expected, *value);
            return {};
        }
        result.push_back(item.get<double>());
    }
    return result;
}

std::vector<std::uint32_t> FieldReader::indices(std::string_view key) {
    const Json* value = find(key);
    if (!value) {
        return {};
    }
    if (!value->is_array()) {
        failType(key, "an array of indices", *value);
        return {};
    }
    std::vector<std::uint32_t> result;
    result.reserve(value->size());
    for (const Json& item : *value) {
        const auto index = jsonToUint(item);
        if (!index || *index >= std::numeric_limits<std::uint32_t>::max()) {
            failType(key, "an array of indices", *value);
            return {};
        }
        result.push_back(static_cast<std::uint32_t>(*index));
    }
    return result;
}

const Json* FieldReader::object(std::string_view key) {
    const Json* value = find(key);
    if (value && !value->is_object()) {
        failType(key, "an object", *value);
        return nullptr;
    }
    return value;
}

const Json* FieldReader::objectIfAny(std::string_view key) const {
    const Json* value = find(key);
    return value && value->is_object() ? value : nullptr;
}

const Json* FieldReader::array(std::string_view key) {
    const Json* value = find(key);
    if (value && !value->is_array()) {
        failType(key, "an array", *value);
        return nullptr;
    }
    return value;
}

Result<void> forEachElement(const Json& root,
                            std::string_view key,
                            std::string_view elementName,
                            const std::function<void(FieldReader&, std::size_t)>& read) {
    const auto it = root.find(key);
    if (it == root.end()) {
        return {};
    }
    if (!it->is_array()) {
        return makeError(ErrorCode::InvalidFormat, "The asset's '" + std::string(key) +
                                                       "' is not an array (got " +
                                                       describeJson(*it) + ").");
    }
    for (std::size_t i = 0; i < it->size(); ++i) {
        FieldReader reader((*it)[i], std::string(elementName) + " " + std::to_string(i));
        if (!reader.failed()) {
            read(reader, i);
        }
        if (reader.failed()) {
            return reader.error();
        }
    }
    return {};
}

const Json* extensionObject(FieldReader& reader, std::string_view name) {
    const Json* extensions = reader.object("extensions");
    if (!extensions) {
        return nullptr;
    }
    const auto it = extensions->find(name);
    if (it == extensions->end()) {
        return nullptr;
    }
    if (!it->is_object()) {
        reader.fail(ErrorCode::InvalidFormat, reader.element() + " has an invalid " +
                                                  std::string(name) + " extension (got " +
                                                  describeJson(*it) + ").");
        return nullptr;
    }
    return &*it;
}

}  // namespace encore::scene
