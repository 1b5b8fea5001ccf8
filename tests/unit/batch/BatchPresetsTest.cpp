// --preset (issue 50): each preset's cameras against the numbers its pipeline published, every
// value with a source, explicit options replacing a preset's, and bad names refused.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "TestPaths.h"
#include "batch/BatchOptionTable.h"
#include "batch/BatchOptionsValidation.h"
#include "batch/BatchPresets.h"
#include "encore/batch/ViewRig.h"

namespace encore::batch {
namespace {

Result<BatchOptions> withOptions(std::vector<std::pair<std::string, std::string>> values,
                                 OptionFront front = OptionFront::CommandLine) {
    std::vector<GivenOption> given;
    for (const auto& [name, value] : values) {
        const BatchOptionDescription* option = findBatchOption(name, front);
        EXPECT_NE(option, nullptr) << name;
        given.push_back({option, value});
    }
    BatchOptions options;
    ENCORE_TRY(applyBatchOptions(options, given, front));
    ENCORE_TRY(validateBatchOptions(options));
    return options;
}

BatchOptions preset(const std::string& name) {
    auto options = withOptions({{"preset", name}});
    EXPECT_TRUE(options.ok()) << name << ": " << (options.ok() ? "" : options.error().message);
    return options.ok() ? *options : BatchOptions{};
}

float degreesOf(float radians) {
    return glm::degrees(radians);
}

glm::vec3 eye(const ViewCamera& view) {
    return glm::vec3(view.cameraToWorld[3]);
}
float elevationOf(const ViewCamera& view) {
    return glm::degrees(std::asin(eye(view).y / glm::length(eye(view))));
}
float azimuthOf(const ViewCamera& view) {
    return glm::degrees(std::atan2(eye(view).x, eye(view).z));
}
void expectAngle(float actual, float expected, const std::string& what) {
    EXPECT_NEAR(std::remainder(actual - expected, 360.0f), 0.0f, 1e-3f) << what;
}

TEST(BatchPresetsTest, EveryValueIsARealOptionWithASource) {
    ASSERT_EQ(presetNames(),
              (std::vector<std::string>{"zero123", "zero123plus", "instantmesh", "wonder3d",
                                        "gobjaverse", "trellis", "mvdream", "objaverse-xl"}));
    for (const BatchPreset& p : batchPresets()) {
        EXPECT_FALSE(p.summary.empty()) << p.name;
        for (const PresetValue& value : p.values) {
            EXPECT_NE(findBatchOption(value.option, OptionFront::CommandLine), nullptr)
                << p.name << ": " << value.option;
            EXPECT_EQ(value.source.rfind("https://", 0), 0u) << p.name << ": " << value.option;
        }
        preset(p.name);  // Applies and validates.
        EXPECT_EQ(preset(p.name).preset, p.name);
    }
    const std::string listing = presetListing();
    EXPECT_NE(listing.find("gobjaverse: "), std::string::npos);
    EXPECT_NE(listing.find("https://github.com/microsoft/TRELLIS"), std::string::npos);
}

TEST(BatchPresetsTest, Zero123) {
    const BatchOptions o = preset("zero123");
    const std::vector<ViewCamera> views = viewCameras(o.views, "m");
    ASSERT_EQ(views.size(), 12u);
    EXPECT_EQ(o.views.distribution, CameraDistribution::Sphere);
    for (const ViewCamera& view : views) {
        EXPECT_NEAR(degreesOf(view.horizontalFovRadians), 49.1343f, 1e-3f);
        EXPECT_GE(glm::length(eye(view)), 1.5f - 1e-5f);
        EXPECT_LE(glm::length(eye(view)), 2.2f + 1e-5f);
    }
    EXPECT_NEAR(2.0 * std::atan(16.0 / 35.0), glm::radians(49.1343), 1e-5);
    EXPECT_TRUE(o.views.normalize);
    EXPECT_EQ(o.renderer.toneMapping.background, render::BackgroundKind::Transparent);
    EXPECT_EQ(o.layout, OutputLayout::Objaverse);
}

TEST(BatchPresetsTest, Zero123Plus) {
    const BatchOptions o = preset("zero123plus");
    const std::vector<ViewCamera> views = viewCameras(o.views, "m");
    ASSERT_EQ(views.size(), 6u);
    const float azimuths[] = {30, 90, 150, 210, 270, 330};
    const float elevations[] = {20, -10, 20, -10, 20, -10};
    for (std::size_t i = 0; i < 6; ++i) {
        expectAngle(azimuthOf(views[i]), azimuths[i], "azimuth " + std::to_string(i));
        EXPECT_NEAR(elevationOf(views[i]), elevations[i], 1e-3f);
        EXPECT_NEAR(degreesOf(views[i].horizontalFovRadians), 30.0f, 1e-4f);
        EXPECT_NEAR(glm::length(eye(views[i])), 2.0f, 1e-5f);
    }
}

TEST(BatchPresetsTest, InstantMesh) {
    const BatchOptions o = preset("instantmesh");
    const std::vector<ViewCamera> views = viewCameras(o.views, "m");
    ASSERT_EQ(views.size(), 32u);
    for (const ViewCamera& view : views) {
        EXPECT_NEAR(degreesOf(view.horizontalFovRadians), 50.0f, 1e-4f);
        // 2.0-3.5 for a model in [-1, 1]: half that in the unit box.
        EXPECT_GE(glm::length(eye(view)), 1.0f - 1e-5f);
        EXPECT_LE(glm::length(eye(view)), 1.75f + 1e-5f);
        EXPECT_GE(elevationOf(view), -22.0f - 1e-3f);
        EXPECT_LE(elevationOf(view), 53.0f + 1e-3f);
    }
    EXPECT_NEAR(glm::degrees(std::asin(-0.75 / 2.0)), -22.0, 0.05);
    EXPECT_NEAR(glm::degrees(std::asin(1.6 / 2.0)), 53.1, 0.05);
}

TEST(BatchPresetsTest, Wonder3d) {
    const BatchOptions o = preset("wonder3d");
    const std::vector<ViewCamera> views = viewCameras(o.views, "m");
    ASSERT_EQ(views.size(), 6u);
    const float azimuths[] = {0, 45, 90, 180, -90, -45};
    for (std::size_t i = 0; i < 6; ++i) {
        EXPECT_EQ(views[i].projection, Projection::Orthographic);
        EXPECT_EQ(views[i].orthoScale, 1.35f);
        expectAngle(azimuthOf(views[i]), azimuths[i], "azimuth " + std::to_string(i));
        EXPECT_NEAR(elevationOf(views[i]), 0.0f, 1e-3f);
        EXPECT_NEAR(glm::length(eye(views[i])), 2.0f, 1e-5f);
    }
    EXPECT_TRUE(o.images.normals);
}

TEST(BatchPresetsTest, GObjaverse) {
    const BatchOptions o = preset("gobjaverse");
    const std::vector<ViewCamera> views = viewCameras(o.views, "m");
    ASSERT_EQ(views.size(), 38u);
    // Blender's azimuth a (from its +X) is Encore's a + 90 (from glTF's +Z).
    for (int i = 0; i < 24; ++i) {
        expectAngle(azimuthOf(views[i]), 15.0f * i + 90.0f, "orbit " + std::to_string(i));
        EXPECT_NEAR(elevationOf(views[i]), 5.0f + 25.0f * i / 23.0f, 1e-3f) << i;
        EXPECT_NEAR(glm::length(eye(views[i])), 1.645f, 1e-5f);
    }
    EXPECT_NEAR(elevationOf(views[24]), 90.0f, 1e-3f);
    EXPECT_NEAR(elevationOf(views[25]), -90.0f, 1e-3f);
    for (int i = 0; i < 12; ++i) {
        const ViewCamera& view = views[26 + i];
        expectAngle(azimuthOf(view), 30.0f * i + 90.0f, "low orbit " + std::to_string(i));
        EXPECT_NEAR(elevationOf(view), -5.0f + 10.0f * i / 11.0f, 1e-3f) << i;
        EXPECT_NEAR(glm::length(eye(view)), 1.9547f, 1e-5f);
    }
    for (const ViewCamera& view : views) {
        EXPECT_NEAR(view.horizontalFovRadians, 0.6911f, 1e-4f);
    }
    EXPECT_EQ(o.width, 512u);
    EXPECT_TRUE(o.images.albedo && o.images.hdr && o.images.material && o.images.normals &&
                o.images.depth);
    EXPECT_EQ(o.images.depthFormat, DepthFormat::Exr);
    EXPECT_EQ(o.cameraConvention, CameraConvention::OpenCv);
    EXPECT_EQ(o.layout, OutputLayout::Gobjaverse);
}

TEST(BatchPresetsTest, Trellis) {
    const BatchOptions o = preset("trellis");
    const std::vector<ViewCamera> views = viewCameras(o.views, "m");
    ASSERT_EQ(views.size(), 150u);
    EXPECT_EQ(o.views.distribution, CameraDistribution::Hammersley);
    for (const ViewCamera& view : views) {
        EXPECT_NEAR(degreesOf(view.horizontalFovRadians), 40.0f, 1e-4f);
        EXPECT_NEAR(glm::length(eye(view)), 2.0f, 1e-5f);
    }
    EXPECT_EQ(o.width, 512u);
}

TEST(BatchPresetsTest, MvDream) {
    const BatchOptions o = preset("mvdream");
    const std::vector<ViewCamera> views = viewCameras(o.views, "m");
    ASSERT_EQ(views.size(), 32u);
    for (std::size_t i = 0; i < views.size(); ++i) {
        const ViewCamera& view = views[i];
        expectAngle(azimuthOf(view), 360.0f * float(i) / 32.0f, "azimuth " + std::to_string(i));
        const float fov = degreesOf(view.horizontalFovRadians);
        EXPECT_GE(fov, 15.0f - 1e-4f);
        EXPECT_LE(fov, 60.0f + 1e-4f);
        EXPECT_GE(elevationOf(view), -1e-3f);
        EXPECT_LE(elevationOf(view), 30.0f + 1e-3f);
        const float relative = glm::length(eye(view)) * std::tan(0.5f * view.horizontalFovRadians);
        EXPECT_GE(relative, 0.9f - 1e-4f);
        EXPECT_LE(relative, 1.1f + 1e-4f);
    }
}

TEST(BatchPresetsTest, ObjaverseXl) {
    const BatchOptions o = preset("objaverse-xl");
    EXPECT_EQ(viewCameras(o.views, "m").size(), 12u);
    EXPECT_EQ(o.layout, OutputLayout::Objaverse);
    EXPECT_EQ(o.views.distance, ValueRange(1.5f, 2.2f));
}

TEST(BatchPresetsTest, AnExplicitOptionReplacesThePresetsValue) {
    auto o = withOptions({{"preset", "trellis"}, {"fov", "30"}, {"size", "256"}});
    ASSERT_TRUE(o.ok()) << o.error().message;
    EXPECT_EQ(o->views.horizontalFovDegrees, ValueRange(30.0f));
    EXPECT_EQ(o->width, 256u);
    EXPECT_EQ(o->views.views, 150u);  // The rest stays the preset's.
    // One that excludes a preset's option drops it: random views replace the fixed azimuths.
    o = withOptions({{"preset", "zero123plus"}, {"random-views", "4"}});
    ASSERT_TRUE(o.ok()) << o.error().message;
    EXPECT_EQ(viewCameras(o->views, "m").size(), 4u);
    EXPECT_TRUE(o->views.azimuthsDegrees.empty());
    // A flag given off in Python turns the preset's off.
    o = withOptions({{"preset", "gobjaverse"}, {"hdr", "false"}}, OptionFront::Python);
    ASSERT_TRUE(o.ok()) << o.error().message;
    EXPECT_FALSE(o->images.hdr);
    EXPECT_TRUE(o->images.albedo);
    // An option that needs one the preset gives is satisfied by it.
    o = withOptions({{"preset", "gobjaverse"}, {"depth-format", "png"}});
    ASSERT_TRUE(o.ok()) << o.error().message;
    EXPECT_EQ(o->images.depthFormat, DepthFormat::Png);
}

TEST(BatchPresetsTest, AnUnknownPresetIsNamedWithTheChoices) {
    auto o = withOptions({{"preset", "zero124"}});
    ASSERT_FALSE(o.ok());
    EXPECT_EQ(o.error().code, ErrorCode::InvalidArgument);
    EXPECT_EQ(o.error().message,
              "--preset takes zero123, zero123plus, instantmesh, wonder3d, gobjaverse, trellis, "
              "mvdream or objaverse-xl (not 'zero124'; did you mean zero123?); list prints them "
              "with their sources.");
}

// docs/batch.md's table of presets is the one the descriptions make (regenerate it from the file
// the failure names).
TEST(BatchPresetsTest, DocsTableIsTheDescription) {
    const std::filesystem::path docs = test::sourceDir() / "docs" / "batch.md";
    std::ifstream file(docs);
    ASSERT_TRUE(file) << docs;
    std::stringstream text;
    text << file.rdbuf();
    const std::string expected = presetsMarkdown();
    if (text.str().find(expected) == std::string::npos) {
        const std::filesystem::path written = test::makeTempDir("batch-presets") / "presets.md";
        std::ofstream(written) << expected;
        ADD_FAILURE() << "docs/batch.md's preset table is not the one the presets make: "
                         "replace it with "
                      << written;
    }
}

}  // namespace
}  // namespace encore::batch
