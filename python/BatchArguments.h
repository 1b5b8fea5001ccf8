#pragma once

// The keyword arguments of the Python module's render_views that describe views and ranges,
// and the inputs of batch and discover_inputs, turned into encore::batch values; bad values raise
// ValueError (pybind11's value_error) with the message the command line would print. (batch()'s
// options are BatchKeywords.h's.)

#include <pybind11/pybind11.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "batch/OptionNames.h"
#include "encore/batch/Batch.h"
#include "encore/batch/BatchInputs.h"

namespace encore::python {

namespace py = pybind11;

// The value `name` names in `table` (batch/OptionNames.h, the command line's too), or ValueError
// naming `keyword` and the names it takes.
template <class Enum>
Enum named(batch::NameTable<Enum> table, const std::string& name, const char* keyword) {
    auto value = batch::parseNamed(table, name, keyword);
    if (!value) {
        throw py::value_error(value.error().message);
    }
    return *value;
}

// A number, or a (min, max) pair drawn from: what distance, fov and the environment's rotation
// and intensity take. `name` names the keyword in the error.
batch::ValueRange valueRange(const py::object& value, const char* name);

// The view rig of the keyword arguments render_views and batch share.
struct RigArguments {
    std::uint32_t views = 12;
    float elevation = 30.0f;
    py::object distance;
    py::object fov;  // None: batch::kDefaultHorizontalFovDegrees.
    batch::CameraDistribution distribution = batch::CameraDistribution::Orbit;
    std::uint64_t seed = 0;
    bool normalize = true;
    float jitter = 0.0f;
    batch::Projection projection = batch::Projection::Perspective;
    float orthoScale = batch::kDefaultOrthoScale;
    // Each view's (or, one value, every view's) azimuth, elevation and distance: None, a number
    // or a sequence of numbers, as --azimuths, --elevations and --distances take them.
    py::object azimuths = py::none();
    py::object elevations = py::none();
    py::object distances = py::none();
};

// The rig, checked as runBatch checks it.
batch::ViewRigOptions rigOptions(const RigArguments& arguments);

// A `variant=` keyword: None, a variant's name, or its index, as text (scene::findVariant).
std::string variantArgument(const py::object& variant);

// `size` is an int (square) or a (width, height) pair.
std::pair<std::uint32_t, std::uint32_t> imageSize(const py::object& size);

// The models a batch renders: a folder, list file or model path (what `encore batch` takes) or
// a sequence of (path, name) pairs (discover_inputs).
std::vector<batch::BatchInput> batchInputs(const py::object& inputs);

// discover_inputs: a folder, list file or model path, or a sequence of model paths.
py::list discoverInputs(const py::object& input);

}  // namespace encore::python
