#include "BatchArguments.h"

#include "batch/BatchOptionsValidation.h"

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

batch::CameraDistribution cameraDistribution(const std::string& name) {
    if (name == "orbit") {
        return batch::CameraDistribution::Orbit;
    }
    if (name == "sphere") {
        return batch::CameraDistribution::Sphere;
    }
    if (name == "upper-hemisphere") {
        return batch::CameraDistribution::UpperHemisphere;
    }
    throw py::value_error(
        "camera_distribution must be \"orbit\", \"sphere\" or "
        "\"upper-hemisphere\"");
}

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
    batch::BatchOptions checked;
    checked.views = rig;
    if (auto valid = batch::validateBatchOptions(checked); !valid) {
        throw py::value_error(valid.error().message);
    }
    return rig;
}

}  // namespace encore::python
