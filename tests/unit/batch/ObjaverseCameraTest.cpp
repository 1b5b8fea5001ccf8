// The .npy camera matrices of `--layout objaverse`: NumPy's version 1.0 header exactly as
// numpy.save writes it, and the Objaverse-XL script's world-to-camera matrix in Blender's frame.

#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "batch/NpyFile.h"
#include "batch/ObjaverseCamera.h"
#include "encore/batch/ViewRig.h"

namespace encore::batch {
namespace {

std::string headerOf(const std::vector<std::uint8_t>& file) {
    const std::size_t length = file[8] | (std::size_t(file[9]) << 8);
    return std::string(reinterpret_cast<const char*>(file.data()) + 10, length);
}

TEST(NpyFileTest, HeaderAsNumpySaveWritesIt) {
    std::vector<double> values(12);
    for (std::size_t i = 0; i < values.size(); ++i) {
        values[i] = double(i) * 0.5 - 1.0;
    }
    const std::vector<std::uint8_t> file = npyFloat64(values, 3, 4);
    // numpy 1.24: np.save(f, np.arange(12.0).reshape(3, 4)) writes these 128 header bytes.
    ASSERT_EQ(file.size(), 128u + 12 * 8);
    EXPECT_EQ(std::memcmp(file.data(), "\x93NUMPY\x01\x00", 8), 0);
    EXPECT_EQ(file[8], 118);
    EXPECT_EQ(file[9], 0);
    EXPECT_EQ(headerOf(file), "{'descr': '<f8', 'fortran_order': False, 'shape': (3, 4), }" +
                                  std::string(58, ' ') + "\n");
    double read[12];
    std::memcpy(read, file.data() + 128, sizeof(read));
    for (std::size_t i = 0; i < 12; ++i) {
        EXPECT_EQ(read[i], values[i]);
    }
}

TEST(NpyFileTest, TheDataStartsOnASixtyFourByteBoundaryForAnyShape) {
    for (const std::uint32_t rows : {0u, 1u, 9u, 10u, 1000u, 123456789u}) {
        const std::vector<double> values(rows < 100 ? std::size_t(rows) * 2 : 0);
        const std::vector<std::uint8_t> file = npyFloat64(values, rows, rows < 100 ? 2 : 0);
        const std::string header = headerOf(file);
        EXPECT_EQ((10 + header.size()) % 64, 0u) << rows;
        EXPECT_EQ(header.back(), '\n');
        EXPECT_NE(header.find("'shape': (" + std::to_string(rows) + ", "), std::string::npos);
    }
}

// A point of the glTF world at `gltf` in Blender's world, as Blender's glTF importer places it.
glm::dvec3 toBlender(const glm::dvec3& gltf) {
    return {gltf.x, -gltf.z, gltf.y};
}

TEST(ObjaverseCameraTest, WorldToCameraInBlendersFrame) {
    // The camera on glTF's +Z axis (Blender's -Y), level, looking at the origin.
    const std::array<double, 12> rt =
        objaverseCameraMatrix(lookAtCameraToWorld({0.0f, 0.0f, 1.5f}, glm::vec3(0.0f)));
    const std::array<double, 12> expected = {1.0, 0.0,  0.0, 0.0,    // x: right, world +X.
                                             0.0, 0.0,  1.0, 0.0,    // y: up, Blender's +Z.
                                             0.0, -1.0, 0.0, -1.5};  // Looking along +Y.
    for (std::size_t i = 0; i < 12; ++i) {
        EXPECT_NEAR(rt[i], expected[i], 1e-6) << i;
    }
}

TEST(ObjaverseCameraTest, MapsBlenderPointsAsTheCameraSeesThem) {
    ViewRigOptions rig;
    rig.distribution = CameraDistribution::Sphere;
    rig.views = 20;
    for (const ViewCamera& view : viewCameras(rig, "model")) {
        const std::array<double, 12> rt = objaverseCameraMatrix(view.cameraToWorld);
        const glm::dmat4 worldToCamera = glm::inverse(glm::dmat4(view.cameraToWorld));
        for (const glm::dvec3 point :
             {glm::dvec3(0.0), glm::dvec3(0.3, -0.2, 0.4), glm::dvec3(-0.5, 0.5, 0.1)}) {
            const glm::dvec3 blender = toBlender(point);
            const glm::dvec3 camera(worldToCamera * glm::dvec4(point, 1.0));
            for (int row = 0; row < 3; ++row) {
                const double mapped = rt[4 * row] * blender.x + rt[4 * row + 1] * blender.y +
                                      rt[4 * row + 2] * blender.z + rt[4 * row + 3];
                EXPECT_NEAR(mapped, camera[row], 1e-5) << row;
            }
        }
    }
}

}  // namespace
}  // namespace encore::batch
