// --poses FILE (issue 50): transforms.json, JSON lists and .npy stacks read back into the cameras
// that wrote them, and every malformed file refused with its name and the problem.

#include <gtest/gtest.h>

#include <fstream>

#include "TestPaths.h"
#include "batch/CameraConvention.h"
#include "batch/NpyFile.h"
#include "batch/PoseFile.h"
#include "batch/TransformsJson.h"
#include "core/FileIO.h"
#include "encore/batch/ViewRig.h"

namespace encore::batch {
namespace {

namespace fs = std::filesystem;

fs::path writeText(const fs::path& path, const std::string& text) {
    std::ofstream(path) << text;
    return path;
}

// A (count, 3, 4) float64 .npy, as numpy.save writes one.
std::string npyStack(const std::vector<double>& values, std::size_t count) {
    std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': (" +
                         std::to_string(count) + ", 3, 4), }";
    header.append(64 - (10 + header.size() + 1) % 64, ' ');
    header += '\n';
    std::string file("\x93NUMPY\x01\x00", 8);
    file += char(header.size() & 0xff);
    file += char(header.size() >> 8);
    file += header;
    file.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(double));
    return file;
}

std::vector<ViewCamera> someViews(Projection projection = Projection::Perspective) {
    ViewRigOptions rig;
    rig.views = 5;
    rig.distribution = CameraDistribution::Sphere;
    rig.distance = ValueRange(1.2f, 2.5f);
    rig.horizontalFovDegrees = ValueRange(20.0f, 70.0f);
    rig.projection = projection;
    rig.orthoScale = 1.4f;
    return viewCameras(rig, "poses");
}

TEST(PoseFileTest, TransformsJsonReadsBackTheSameCamerasInEveryConvention) {
    const fs::path dir = test::makeTempDir("pose-file-transforms");
    for (const Projection projection : {Projection::Perspective, Projection::Orthographic}) {
        const std::vector<ViewCamera> views = someViews(projection);
        for (const CameraConvention convention :
             {CameraConvention::OpenGl, CameraConvention::OpenCv, CameraConvention::Blender}) {
            const fs::path path =
                writeText(dir / "transforms.json",
                          transformsJson(views, 64, 48, {}, 0.0, nullptr, {}, convention).dump());
            // The file names its convention: the option given does not override it.
            auto read = readPoseFile(path, "--poses", CameraConvention::OpenGl, ViewRigOptions{});
            ASSERT_TRUE(read.ok()) << read.error().message;
            EXPECT_EQ(*read, views) << int(projection) << " " << int(convention);
        }
    }
}

TEST(PoseFileTest, AJsonListTakesTheRigsLens) {
    const fs::path dir = test::makeTempDir("pose-file-list");
    const fs::path path =
        writeText(dir / "cams.json",
                  "[[[1,0,0,0],[0,1,0,0],[0,0,1,2],[0,0,0,1]],"
                  " {\"transform_matrix\": [[1,0,0,0],[0,1,0,0],[0,0,1,3],[0,0,0,1]],"
                  "  \"camera_angle_x\": 0.5}]");
    ViewRigOptions rig;
    rig.horizontalFovDegrees = 40.0f;
    auto read = readPoseFile(path, "--poses", std::nullopt, rig);
    ASSERT_TRUE(read.ok()) << read.error().message;
    ASSERT_EQ(read->size(), 2u);
    EXPECT_EQ((*read)[0].cameraToWorld[3], glm::vec4(0.0f, 0.0f, 2.0f, 1.0f));
    EXPECT_FLOAT_EQ((*read)[0].horizontalFovRadians, glm::radians(40.0f));
    EXPECT_FLOAT_EQ((*read)[1].horizontalFovRadians, 0.5f);
    // In OpenCV's axes the same matrix is a camera turned about X: its -Z is OpenCV's +Z.
    auto opencv = readPoseFile(path, "--poses", CameraConvention::OpenCv, rig);
    ASSERT_TRUE(opencv.ok());
    EXPECT_EQ((*opencv)[0].cameraToWorld[2], glm::vec4(0.0f, 0.0f, -1.0f, 0.0f));
    // A range of fields of view leaves the first camera without one.
    rig.horizontalFovDegrees = ValueRange(30.0f, 60.0f);
    auto ranged = readPoseFile(path, "--poses", std::nullopt, rig);
    ASSERT_FALSE(ranged.ok());
    EXPECT_NE(ranged.error().message.find("camera 0: no field of view"), std::string::npos)
        << ranged.error().message;
}

TEST(PoseFileTest, ANpyStackReadsBackTheObjaverseMatrices) {
    const fs::path dir = test::makeTempDir("pose-file-npy");
    const std::vector<ViewCamera> views = someViews();
    for (const CameraConvention convention :
         {CameraConvention::Blender, CameraConvention::OpenCv}) {
        std::vector<double> stack;
        for (const ViewCamera& view : views) {
            const auto rows = worldToCameraRows(view.cameraToWorld, convention);
            stack.insert(stack.end(), rows.begin(), rows.end());
        }
        const std::string text = npyStack(stack, views.size());
        const fs::path path = dir / "cams.npy";
        std::ofstream(path, std::ios::binary) << text;
        ViewRigOptions rig;
        rig.horizontalFovDegrees = 50.0f;
        auto read = readPoseFile(path, "--poses",
                                 convention == CameraConvention::Blender
                                     ? std::nullopt
                                     : std::optional<CameraConvention>(convention),
                                 rig);
        ASSERT_TRUE(read.ok()) << read.error().message;
        ASSERT_EQ(read->size(), views.size());
        for (std::size_t i = 0; i < views.size(); ++i) {
            for (int column = 0; column < 4; ++column) {
                for (int row = 0; row < 3; ++row) {
                    EXPECT_NEAR((*read)[i].cameraToWorld[column][row],
                                views[i].cameraToWorld[column][row], 1e-5f);
                }
            }
            EXPECT_FLOAT_EQ((*read)[i].horizontalFovRadians, glm::radians(50.0f));
        }
    }
}

TEST(PoseFileTest, MalformedFilesNameTheFileAndTheProblem) {
    const fs::path dir = test::makeTempDir("pose-file-bad");
    const ViewRigOptions rig;
    const auto message = [&](const std::string& name, const std::string& text) {
        const fs::path path = writeText(dir / name, text);
        auto read = readPoseFile(path, "--poses", std::nullopt, rig);
        EXPECT_FALSE(read.ok()) << name;
        if (read.ok()) {
            return std::string();
        }
        EXPECT_EQ(read.error().code, ErrorCode::InvalidArgument);
        EXPECT_NE(read.error().message.find("--poses '" + path.string() + "': "), std::string::npos)
            << read.error().message;
        return read.error().message;
    };
    EXPECT_NE(message("a.json", "{\"frames\": [").find("not valid JSON"), std::string::npos);
    EXPECT_NE(message("b.json", "{\"camera_angle_x\": 1}").find("needs \"frames\""),
              std::string::npos);
    EXPECT_NE(message("c.json", "[]").find("holds no cameras"), std::string::npos);
    EXPECT_NE(message("d.json", "[[[1,0,0],[0,1,0],[0,0,1]]]")
                  .find("camera 0: the camera-to-"
                        "world matrix must be 4 rows"),
              std::string::npos);
    EXPECT_NE(message("e.json", "[[[2,0,0,0],[0,1,0,0],[0,0,1,2],[0,0,0,1]]]")
                  .find("camera 0: the matrix is not a rigid camera pose"),
              std::string::npos);
    EXPECT_NE(message("f.json", "{\"camera_convention\": \"directx\", \"frames\": []}")
                  .find("\"camera_convention\" must be"),
              std::string::npos);
    EXPECT_NE(message("g.json", "{\"frames\": [{\"file_path\": \"./000\"}]}")
                  .find("camera 0: no \"transform_matrix\""),
              std::string::npos);
    EXPECT_NE(message("h.npy", std::string("\x93NUMPY\x01\x00\x10\x00{'descr': '<i4'}", 26))
                  .find("float32 or float64"),
              std::string::npos);
    const std::vector<double> values(8, 0.0);
    const std::vector<std::uint8_t> wrongShape = npyFloat64(values, 2, 4);
    EXPECT_NE(message("i.npy", std::string(wrongShape.begin(), wrongShape.end()))
                  .find("shape (N, 3, 4) or (N, 4, 4) is needed, not (2, 4)"),
              std::string::npos);
    auto missing = readPoseFile(dir / "none.json", "poses", std::nullopt, rig);
    ASSERT_FALSE(missing.ok());
    EXPECT_EQ(missing.error().code, ErrorCode::InvalidArgument);
    EXPECT_EQ(missing.error().message.rfind("poses '", 0), 0u) << missing.error().message;
}

}  // namespace
}  // namespace encore::batch
