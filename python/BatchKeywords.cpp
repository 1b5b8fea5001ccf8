#include "BatchKeywords.h"

#include <cstdio>
#include <string>

#include "ViewPasses.h"
#include "batch/OptionValues.h"

namespace encore::python {

namespace {

using batch::OptionForm;

// The batch option (its command-line name) a pass of passes= turns on; empty for "rgba".
const char* passOption(batch::ViewImage kind) {
    switch (kind) {
        case batch::ViewImage::Color:
            return "";
        case batch::ViewImage::Normal:
            return "normals";
        case batch::ViewImage::Depth:
            return "depth";
        case batch::ViewImage::Albedo:
            return "albedo";
        case batch::ViewImage::Material:
            return "material";
        case batch::ViewImage::Segmentation:
            return "segmentation";
        case batch::ViewImage::Hdr:
            return "hdr";
        case batch::ViewImage::Coordinates:
            return "coordinates";
    }
    return "";
}

bool isInteger(const py::handle& value) {
    return py::isinstance<py::int_>(value) && !py::isinstance<py::bool_>(value);
}

bool isNumber(const py::handle& value) {
    return isInteger(value) || py::isinstance<py::float_>(value);
}

// A float as text that strtof reads back to the same float, as the keyword was cast before.
std::string numberText(const py::handle& value) {
    if (isInteger(value)) {
        return py::str(value);
    }
    char text[32];
    std::snprintf(text, sizeof(text), "%.9g", double(value.cast<float>()));
    return text;
}

// A (first, second) pair of numbers, as "first<separator>second".
std::optional<std::string> pairText(const py::handle& value, const char* separator) {
    if (!py::isinstance<py::tuple>(value) && !py::isinstance<py::list>(value)) {
        return std::nullopt;
    }
    const py::sequence pair = py::reinterpret_borrow<py::sequence>(value);
    if (pair.size() != 2 || !isNumber(pair[0]) || !isNumber(pair[1])) {
        return std::nullopt;
    }
    return numberText(pair[0]) + separator + numberText(pair[1]);
}

[[noreturn]] void wrongType(const std::string& keyword, const std::string& takes) {
    throw py::type_error("batch() keyword " + keyword + " takes " + takes + ".");
}

// The text the command line would give for `value`.
std::string valueText(const batch::BatchOptionDescription& option, const py::handle& value) {
    const std::string keyword = option.pythonKeyword();
    switch (option.form) {
        case OptionForm::Flag:
            if (!py::isinstance<py::bool_>(value)) {
                wrongType(keyword, "True or False");
            }
            return value.cast<bool>() != option.keywordNegated ? "true" : "false";
        case OptionForm::WholeNumber:
            if (!isInteger(value)) {
                wrongType(keyword, "an int");
            }
            // A negative int as its text: the option's check names it.
            return py::str(value);
        case OptionForm::Number:
            if (!isNumber(value)) {
                wrongType(keyword, "a number");
            }
            return numberText(value);
        case OptionForm::Range:
            if (isNumber(value)) {
                return numberText(value);
            }
            if (auto pair = pairText(value, ":")) {
                return *pair;
            }
            if (py::isinstance<py::str>(value)) {
                return value.cast<std::string>();  // "random", where the option takes it.
            }
            // Any other sequence: the option's own message says what it takes.
            throw py::value_error(keyword + " must be a number or a (min, max) pair");
        case OptionForm::ImageSize:
            if (isInteger(value)) {
                return py::str(value);
            }
            if (auto pair = pairText(value, "x")) {
                return *pair;
            }
            throw py::value_error(keyword +
                                  " must be an int or a (width, height) pair, each from 1 to 8192");
        case OptionForm::ByteSize:
            if (isInteger(value)) {
                return py::str(value);
            }
            if (!py::isinstance<py::str>(value)) {
                wrongType(keyword, "an int or a str such as \"1GiB\"");
            }
            return value.cast<std::string>();
        case OptionForm::NumberList: {
            if (isNumber(value)) {
                return numberText(value);
            }
            if (!py::isinstance<py::tuple>(value) && !py::isinstance<py::list>(value)) {
                wrongType(keyword, "a sequence of numbers");
            }
            std::string text;
            for (const py::handle item : py::reinterpret_borrow<py::sequence>(value)) {
                if (!isNumber(item)) {
                    wrongType(keyword, "a sequence of numbers");
                }
                text += (text.empty() ? "" : ",") + numberText(item);
            }
            return text;
        }
        case OptionForm::Text:
            if (option.name == "variant" && isInteger(value)) {
                return py::str(value);  // A variant's index.
            }
            if (py::hasattr(value, "__fspath__")) {
                return py::str(py::module_::import("os").attr("fspath")(value));
            }
            if (!py::isinstance<py::str>(value)) {
                wrongType(keyword, option.name == "variant" ? "a str or an int" : "a str");
            }
            return value.cast<std::string>();
    }
    return {};
}

}  // namespace

std::vector<batch::GivenOption> givenBatchOptions(const py::kwargs& keywords) {
    std::vector<batch::GivenOption> given;
    for (const auto& [key, value] : keywords) {
        const std::string keyword = py::str(key);
        if (keyword == "passes") {
            if (value.is_none()) {
                continue;
            }
            for (const batch::ViewImage kind :
                 passKinds(py::reinterpret_borrow<py::object>(value))) {
                if (*passOption(kind)) {
                    given.push_back(
                        {batch::findBatchOption(passOption(kind), batch::OptionFront::CommandLine),
                         "true"});
                }
            }
            continue;
        }
        const batch::BatchOptionDescription* option =
            batch::findBatchOption(keyword, batch::OptionFront::Python);
        if (!option) {
            std::vector<std::string> names = batch::batchOptionNames(batch::OptionFront::Python);
            names.push_back("passes");
            const std::string nearest = batch::nearestName(keyword, names);
            throw py::type_error("batch() got an unexpected keyword argument '" + keyword + "'" +
                                 (nearest.empty() ? std::string(" (docs/batch.md#options)")
                                                  : "; did you mean '" + nearest + "'?"));
        }
        if (value.is_none()) {
            continue;  // The option's default.
        }
        given.push_back({option, valueText(*option, value)});
    }
    return given;
}

std::string batchKeywordsDocstring() {
    return "passes (a sequence of \"rgba\", \"albedo\", \"normal\", \"material\", "
           "\"segmentation\", \"depth\", \"hdr\", \"coordinates\", default None): the images "
           "beside the colour "
           "ones, as render_views names them (the same as albedo=True, normals=True, ...).\n";
}

}  // namespace encore::python
