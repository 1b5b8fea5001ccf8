#include "batch/PoseFile.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <string>

#include <nlohmann/json.hpp>

#include "batch/CameraConvention.h"
#include "batch/OptionNames.h"
#include "core/FileIO.h"

namespace encore::batch {
namespace {

using nlohmann::json;

// Errors about the file say which option and file they are about.
struct PoseErrors {
    std::string prefix;  // "--poses 'cams.json'"

    Error at(const std::string& message) const {
        return makeError(ErrorCode::InvalidArgument, prefix + ": " + message);
    }
    Error at(std::size_t index, const std::string& message) const {
        return at("camera " + std::to_string(index) + ": " + message);
    }
};

// A camera-to-world matrix must be rigid: orthonormal axes, finite, a last row of 0 0 0 1.
bool rigid(const glm::dmat4& matrix) {
    for (int column = 0; column < 4; ++column) {
        for (int row = 0; row < 4; ++row) {
            if (!std::isfinite(matrix[column][row])) {
                return false;
            }
        }
    }
    if (std::abs(matrix[0][3]) > 1e-6 || std::abs(matrix[1][3]) > 1e-6 ||
        std::abs(matrix[2][3]) > 1e-6 || std::abs(matrix[3][3] - 1.0) > 1e-6) {
        return false;
    }
    const glm::dmat3 axes(matrix);
    const glm::dmat3 gram = glm::transpose(axes) * axes;
    constexpr double kTolerance = 1e-3;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            if (std::abs(gram[i][j] - (i == j ? 1.0 : 0.0)) > kTolerance) {
                return false;
            }
        }
    }
    return glm::determinant(axes) > 0.0;
}

// What a file leaves to the rig: its lens.
struct DefaultLens {
    Projection projection = Projection::Perspective;
    float orthoScale = 0.0f;
    std::optional<float> fovRadians;  // Unset when the rig draws it from a range.
};

DefaultLens defaultLens(const ViewRigOptions& rig) {
    DefaultLens lens;
    lens.projection = rig.projection;
    lens.orthoScale = rig.orthoScale;
    if (rig.horizontalFovDegrees.fixed()) {
        lens.fovRadians = glm::radians(rig.horizontalFovDegrees.min);
    }
    return lens;
}

// A view from its OpenGL camera-to-world and lens.
Result<ViewCamera> makeView(const glm::dmat4& openGl,
                            const DefaultLens& lens,
                            std::optional<double> fovRadians,
                            std::size_t index,
                            const PoseErrors& errors) {
    if (!rigid(openGl)) {
        return errors.at(index,
                         "the matrix is not a rigid camera pose (orthonormal axes, a last row "
                         "of 0 0 0 1, finite numbers).");
    }
    ViewCamera view;
    view.cameraToWorld = glm::mat4(openGl);
    view.projection = lens.projection;
    if (lens.projection == Projection::Orthographic) {
        view.orthoScale = lens.orthoScale;
        return view;
    }
    if (!fovRadians) {
        if (!lens.fovRadians) {
            return errors.at(index,
                             "no field of view in the file, and --fov gives a range; give one "
                             "value.");
        }
        fovRadians = *lens.fovRadians;
    }
    if (!(*fovRadians > 0.0 && *fovRadians < M_PI)) {
        return errors.at(index, "the field of view (" + std::to_string(*fovRadians) +
                                    " radians) must lie in (0, pi).");
    }
    view.horizontalFovRadians = float(*fovRadians);
    return view;
}

// A 4x4 matrix written as 4 rows of 4 numbers.
std::optional<glm::dmat4> matrixFromRows(const json& rows) {
    if (!rows.is_array() || rows.size() != 4) {
        return std::nullopt;
    }
    glm::dmat4 matrix(1.0);
    for (int row = 0; row < 4; ++row) {
        if (!rows[row].is_array() || rows[row].size() != 4) {
            return std::nullopt;
        }
        for (int column = 0; column < 4; ++column) {
            if (!rows[row][column].is_number()) {
                return std::nullopt;
            }
            matrix[column][row] = rows[row][column].get<double>();  // glm: [column][row].
        }
    }
    return matrix;
}

// A frame's (or the file's) lens, where it says one.
Result<DefaultLens> lensOf(const json& object, DefaultLens lens, const PoseErrors& errors) {
    if (const auto projection = object.find("projection"); projection != object.end()) {
        const auto kind = projection->is_string()
                              ? valueNamed(projectionNames(), projection->get<std::string>())
                              : std::nullopt;
        if (!kind) {
            return errors.at("\"projection\" must be \"perspective\" or \"orthographic\".");
        }
        lens.projection = *kind;
    }
    if (const auto scale = object.find("ortho_scale"); scale != object.end()) {
        if (!scale->is_number() || !(scale->get<double>() > 0.0)) {
            return errors.at("\"ortho_scale\" must be a positive number.");
        }
        lens.orthoScale = scale->get<float>();
    }
    if (const auto fov = object.find("camera_angle_x"); fov != object.end()) {
        if (!fov->is_number()) {
            return errors.at("\"camera_angle_x\" must be a number (radians).");
        }
        lens.fovRadians = fov->get<float>();
    }
    return lens;
}

Result<std::vector<ViewCamera>> readJsonPoses(const std::vector<std::uint8_t>& bytes,
                                              std::optional<CameraConvention> given,
                                              const ViewRigOptions& rig,
                                              const PoseErrors& errors) {
    const json file = json::parse(bytes.begin(), bytes.end(), nullptr, /*allow_exceptions=*/false);
    if (file.is_discarded()) {
        return errors.at("not valid JSON (nor a .npy file).");
    }
    CameraConvention convention = given.value_or(CameraConvention::OpenGl);
    DefaultLens fileLens = defaultLens(rig);
    const json* frames = &file;
    if (file.is_object()) {
        const auto found = file.find("frames");
        if (found == file.end() || !found->is_array()) {
            return errors.at("a JSON object needs \"frames\", a list (a transforms.json).");
        }
        frames = &*found;
        if (const auto named = file.find("camera_convention"); named != file.end()) {
            const auto recorded =
                named->is_string() ? valueNamed(cameraConventionNames(), named->get<std::string>())
                                   : std::nullopt;
            if (!recorded) {
                return errors.at("\"camera_convention\" must be opengl, opencv or blender.");
            }
            convention = *recorded;
        }
        ENCORE_TRY_ASSIGN(fileLens, lensOf(file, fileLens, errors));
    } else if (!file.is_array()) {
        return errors.at("a pose file holds a transforms.json object or a list of cameras.");
    }
    if (frames->empty()) {
        return errors.at("it holds no cameras.");
    }
    if (frames->size() > kMaxPoses) {
        return errors.at("it holds " + std::to_string(frames->size()) + " cameras, more than " +
                         std::to_string(kMaxPoses) + ".");
    }
    std::vector<ViewCamera> views;
    for (std::size_t index = 0; index < frames->size(); ++index) {
        const json& frame = (*frames)[index];
        const json* rows = &frame;
        DefaultLens lens = fileLens;
        std::optional<double> fov;
        if (frame.is_object()) {
            const auto matrix = frame.find("transform_matrix");
            if (matrix == frame.end()) {
                return errors.at(index, "no \"transform_matrix\".");
            }
            rows = &*matrix;
            ENCORE_TRY_ASSIGN(lens, lensOf(frame, fileLens, errors));
        }
        const std::optional<glm::dmat4> matrix = matrixFromRows(*rows);
        if (!matrix) {
            return errors.at(index, "the camera-to-world matrix must be 4 rows of 4 numbers.");
        }
        if (lens.fovRadians) {
            fov = *lens.fovRadians;
        }
        ENCORE_TRY_ASSIGN(ViewCamera view, makeView(cameraToWorldFrom(*matrix, convention), lens,
                                                    fov, index, errors));
        views.push_back(view);
    }
    return views;
}

// NumPy's header: "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3, 4), }".
struct NpyHeader {
    std::size_t valueBytes = 0;  // 4 or 8.
    std::vector<std::size_t> shape;
    std::size_t dataOffset = 0;
};

Result<NpyHeader> parseNpyHeader(const std::vector<std::uint8_t>& bytes, const PoseErrors& errors) {
    const Error malformed = errors.at("a malformed .npy header.");
    if (bytes.size() < 10 || std::memcmp(bytes.data(), "\x93NUMPY", 6) != 0) {
        return malformed;
    }
    const std::uint8_t major = bytes[6];
    std::size_t headerSize = 0;
    std::size_t start = 0;
    if (major == 1) {
        headerSize = bytes[8] | (std::size_t(bytes[9]) << 8);
        start = 10;
    } else if ((major == 2 || major == 3) && bytes.size() >= 12) {
        headerSize = bytes[8] | (std::size_t(bytes[9]) << 8) | (std::size_t(bytes[10]) << 16) |
                     (std::size_t(bytes[11]) << 24);
        start = 12;
    } else {
        return malformed;
    }
    if (headerSize > bytes.size() - start) {
        return malformed;
    }
    const std::string header(bytes.begin() + std::ptrdiff_t(start),
                             bytes.begin() + std::ptrdiff_t(start + headerSize));
    NpyHeader parsed;
    parsed.dataOffset = start + headerSize;
    if (header.find("'descr': '<f8'") != std::string::npos) {
        parsed.valueBytes = 8;
    } else if (header.find("'descr': '<f4'") != std::string::npos) {
        parsed.valueBytes = 4;
    } else {
        return errors.at("a .npy of little-endian float32 or float64 is needed (the header says " +
                         header.substr(0, header.find(',')) + ").");
    }
    if (header.find("'fortran_order': False") == std::string::npos) {
        return errors.at("a .npy in C order is needed, not Fortran order.");
    }
    const std::size_t open = header.find("'shape': (");
    const std::size_t close = open == std::string::npos ? open : header.find(')', open);
    if (close == std::string::npos) {
        return malformed;
    }
    const std::string dims = header.substr(open + 10, close - open - 10);
    std::size_t position = 0;
    while (position < dims.size()) {
        while (position < dims.size() && (dims[position] == ' ' || dims[position] == ',')) {
            ++position;
        }
        if (position == dims.size()) {
            break;
        }
        std::size_t value = 0;
        std::size_t digits = 0;
        while (position < dims.size() && dims[position] >= '0' && dims[position] <= '9' &&
               digits < 9) {
            value = value * 10 + std::size_t(dims[position] - '0');
            ++position;
            ++digits;
        }
        if (digits == 0) {
            return malformed;
        }
        parsed.shape.push_back(value);
    }
    return parsed;
}

Result<std::vector<ViewCamera>> readNpyPoses(const std::vector<std::uint8_t>& bytes,
                                             std::optional<CameraConvention> given,
                                             const ViewRigOptions& rig,
                                             const PoseErrors& errors) {
    static_assert(std::endian::native == std::endian::little, "'<f8' is little-endian");
    ENCORE_TRY_ASSIGN(const NpyHeader header, parseNpyHeader(bytes, errors));
    std::vector<std::size_t> shape = header.shape;
    if (shape.size() == 2) {
        shape.insert(shape.begin(), 1);
    }
    if (shape.size() != 3 || (shape[1] != 3 && shape[1] != 4) || shape[2] != 4 || shape[0] == 0) {
        std::string text;
        for (std::size_t dim : header.shape) {
            text += (text.empty() ? "" : ", ") + std::to_string(dim);
        }
        return errors.at("a .npy of shape (N, 3, 4) or (N, 4, 4) is needed, not (" + text + ").");
    }
    if (shape[0] > kMaxPoses) {
        return errors.at("it holds " + std::to_string(shape[0]) + " cameras, more than " +
                         std::to_string(kMaxPoses) + ".");
    }
    const std::size_t values = shape[0] * shape[1] * shape[2];
    if (bytes.size() - header.dataOffset < values * header.valueBytes) {
        return errors.at("the .npy file ends before its " + std::to_string(values) + " values.");
    }
    const auto value = [&](std::size_t index) {
        const std::uint8_t* at = bytes.data() + header.dataOffset + index * header.valueBytes;
        if (header.valueBytes == 8) {
            double number = 0.0;
            std::memcpy(&number, at, 8);
            return number;
        }
        float number = 0.0f;
        std::memcpy(&number, at, 4);
        return double(number);
    };
    const CameraConvention convention = given.value_or(CameraConvention::Blender);
    const DefaultLens lens = defaultLens(rig);
    std::vector<ViewCamera> views;
    for (std::size_t camera = 0; camera < shape[0]; ++camera) {
        glm::dmat4 worldToCamera(1.0);
        for (std::size_t row = 0; row < shape[1]; ++row) {
            for (std::size_t column = 0; column < 4; ++column) {
                worldToCamera[int(column)][int(row)] =
                    value((camera * shape[1] + row) * 4 + column);
            }
        }
        // Rigid or not, makeView says; the inverse of a rigid world-to-camera is exact enough.
        const glm::dmat4 toWorld = glm::inverse(worldToCamera);
        ENCORE_TRY_ASSIGN(ViewCamera view, makeView(cameraToWorldFrom(toWorld, convention), lens,
                                                    std::nullopt, camera, errors));
        views.push_back(view);
    }
    return views;
}

}  // namespace

Result<std::vector<ViewCamera>> readPoseFile(const std::filesystem::path& path,
                                             std::string_view shown,
                                             std::optional<CameraConvention> convention,
                                             const ViewRigOptions& rig) {
    const PoseErrors errors{std::string(shown) + " '" + path.string() + "'"};
    auto bytes = readFile(path);
    if (!bytes) {
        return errors.at(bytes.error().message);
    }
    if (bytes->size() >= 6 && std::memcmp(bytes->data(), "\x93NUMPY", 6) == 0) {
        return readNpyPoses(*bytes, convention, rig, errors);
    }
    return readJsonPoses(*bytes, convention, rig, errors);
}

}  // namespace encore::batch
