#include "BatchArguments.h"

#include "ModuleErrors.h"
#include "batch/BatchOptionsValidation.h"
#include "encore/batch/BatchInputs.h"

#include <filesystem>

namespace encore::python {

batch::ValueRange valueRange(const py::object& value, const char* name) {
    if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) {
        return value.cast<float>();
    }
    if (py::isinstance<py::tuple>(value) || py::isinstance<py::list>(value)) {
        const py::sequence pair = value;
        if (pair.size() == 2) {
            return {pair[0].cast<float>(), pair[1].cast<float>()};
        }
    }
    throw py::value_error(std::string(name) + " must be a number or a (min, max) pair");
}

namespace {

// A sequence of numbers, or one number (None: empty), for the list keyword `name`.
std::vector<float> numberList(const py::object& values, const char* name) {
    if (values.is_none()) {
        return {};
    }
    if (py::isinstance<py::float_>(values) || py::isinstance<py::int_>(values)) {
        return {values.cast<float>()};  // One value for every view, as batch() takes it.
    }
    if (py::isinstance<py::str>(values) || !py::isinstance<py::sequence>(values)) {
        throw py::value_error(std::string(name) + " must be None or a sequence of numbers");
    }
    std::vector<float> numbers;
    for (const py::handle value : values) {
        try {
            numbers.push_back(value.cast<float>());  // NumPy's numbers too.
        } catch (const py::cast_error&) {
            throw py::value_error(std::string(name) + " must be None or a sequence of numbers");
        }
    }
    if (numbers.empty()) {
        throw py::value_error(std::string(name) + " names no value: give None or some numbers");
    }
    return numbers;
}

}  // namespace

batch::ViewRigOptions rigOptions(const RigArguments& arguments) {
    if (arguments.views < 1) {
        throw py::value_error("views must be at least 1");
    }
    batch::ViewRigOptions rig;
    rig.views = arguments.views;
    rig.elevationDegrees = arguments.elevation;
    rig.distance = valueRange(arguments.distance, "distance");
    if (!arguments.fov.is_none()) {
        rig.horizontalFovDegrees = valueRange(arguments.fov, "fov");
    }
    rig.distribution = arguments.distribution;
    rig.seed = arguments.seed;
    rig.normalize = arguments.normalize;
    rig.jitterDegrees = arguments.jitter;
    rig.projection = arguments.projection;
    rig.orthoScale = arguments.orthoScale;
    rig.azimuthsDegrees = numberList(arguments.azimuths, "azimuths");
    rig.elevationsDegrees = numberList(arguments.elevations, "elevations");
    rig.distances = numberList(arguments.distances, "distances");
    batch::BatchOptions checked;
    checked.views = rig;
    if (auto valid = batch::validateBatchOptions(checked); !valid) {
        throw py::value_error(valid.error().message);
    }
    return rig;
}

// A `variant=` keyword: None, a variant's name, or its index, as text (scene::findVariant).
std::string variantArgument(const py::object& variant) {
    if (variant.is_none()) {
        return {};
    }
    if (py::isinstance<py::int_>(variant) && !py::isinstance<py::bool_>(variant)) {
        return std::to_string(variant.cast<long long>());
    }
    if (py::isinstance<py::str>(variant)) {
        return variant.cast<std::string>();
    }
    throw py::type_error("variant must be None, a variant's name (str) or its index (int)");
}

// `size` is an int (square) or a (width, height) pair.
std::pair<std::uint32_t, std::uint32_t> imageSize(const py::object& size) {
    long width = 0;
    long height = 0;
    if (py::isinstance<py::int_>(size)) {
        width = height = size.cast<long>();
    } else {
        auto pair = size.cast<std::pair<long, long>>();
        width = pair.first;
        height = pair.second;
    }
    if (width < 1 || height < 1 || width > 8192 || height > 8192) {
        throw py::value_error("size must be an int or a (width, height) pair, each from 1 to 8192");
    }
    return {std::uint32_t(width), std::uint32_t(height)};
}

// The models a batch renders: a folder, list file or model path (what `encore batch` takes) or
// a sequence of (path, name) pairs (discover_inputs).
std::vector<batch::BatchInput> batchInputs(const py::object& inputs) {
    if (py::isinstance<py::str>(inputs) || py::hasattr(inputs, "__fspath__")) {
        const std::string path = py::str(py::module_::import("os").attr("fspath")(inputs));
        Result<std::vector<batch::BatchInput>> discovered =
            makeError(ErrorCode::InvalidArgument, "");
        {
            py::gil_scoped_release release;
            discovered = batch::discoverInputs(path);
        }
        return valueOrThrow(std::move(discovered));
    }
    const py::object fspath = py::module_::import("os").attr("fspath");
    const auto isPath = [](const py::handle item) {
        return py::isinstance<py::str>(item) || py::hasattr(item, "__fspath__");
    };
    std::vector<std::filesystem::path> paths;
    std::vector<batch::BatchInput> listed;
    for (const py::handle item : inputs) {
        if (isPath(item)) {
            paths.emplace_back(py::str(fspath(item)).cast<std::string>());
            continue;
        }
        if (!py::isinstance<py::sequence>(item) || py::len(item) != 2 ||
            !isPath(item[py::int_(0)]) || !py::isinstance<py::str>(item[py::int_(1)])) {
            throw py::type_error(
                "inputs takes a folder, a list file or a model path, a sequence of model paths, "
                "or (path, name) pairs from encore.discover_inputs; not an item " +
                py::repr(item).cast<std::string>());
        }
        const std::string name = py::str(item[py::int_(1)]);
        if (name.empty()) {
            throw py::value_error("every input needs a non-empty output name");
        }
        listed.push_back({py::str(fspath(item[py::int_(0)])).cast<std::string>(), name});
    }
    if (!paths.empty() && !listed.empty()) {
        throw py::type_error(
            "inputs takes model paths or (path, name) pairs, not both in one sequence");
    }
    // Named as discover_inputs names them: relative to the deepest folder holding them all.
    return paths.empty() ? listed : valueOrThrow(batch::listedInputs(paths));
}

// discover_inputs: a folder, list file or model path, or a sequence of model paths.
py::list discoverInputs(const py::object& input) {
    const std::vector<batch::BatchInput> inputs = batchInputs(input);
    py::list pairs;
    for (const batch::BatchInput& model : inputs) {
        pairs.append(py::make_tuple(model.path.string(), model.name));
    }
    return pairs;
}

}  // namespace encore::python
