// The lighting a batch draws per model: the environment folder's files, and choices that depend
// on the seed and the model's name only.

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>

#include "TestPaths.h"
#include "batch/ModelSeed.h"
#include "encore/batch/BatchLighting.h"

namespace encore::batch {
namespace {

namespace fs = std::filesystem;

TEST(BatchLightingTest, EnvironmentFilesAreTheFoldersHdrFilesSorted) {
    const fs::path dir = test::makeTempDir("batch-lighting-files");
    for (const char* name : {"b.hdr", "a.HDR", "notes.txt", "c.exr"}) {
        std::ofstream(dir / name) << "x";
    }
    fs::create_directories(dir / "nested.hdr");  // A folder, not a file.
    auto files = environmentFiles(dir);
    ASSERT_TRUE(files.ok()) << files.error().message;
    EXPECT_EQ(*files, (std::vector<fs::path>{dir / "a.HDR", dir / "b.hdr"}));

    auto missing = environmentFiles(dir / "absent");
    ASSERT_FALSE(missing.ok());
    EXPECT_EQ(missing.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(missing.error().message.find("is not a folder"), std::string::npos);
    const fs::path empty = test::makeTempDir("batch-lighting-empty");
    std::ofstream(empty / "readme.txt") << "x";
    auto none = environmentFiles(empty);
    ASSERT_FALSE(none.ok());
    EXPECT_NE(none.error().message.find("holds no Radiance .hdr file"), std::string::npos);
}

TEST(BatchLightingTest, WithoutVariationTheBaseLightingIsRecorded) {
    render::LightingParameters base;
    base.environmentIntensity = 2.5f;
    base.environmentRotationRadians = 0.5f;
    const ModelLighting lighting = modelLighting({}, {}, base, 1, "m");
    EXPECT_TRUE(lighting.environmentFile.empty());
    EXPECT_EQ(lighting.environment, "studio");
    EXPECT_EQ(lighting.intensity, 2.5f);
    EXPECT_EQ(lighting.rotationRadians, 0.5f);
    EXPECT_NEAR(lighting.rotationDegrees, 28.6479f, 1e-3f);
    LightingVariation named;
    named.environmentName = "sky.hdr";
    EXPECT_EQ(modelLighting(named, {}, base, 1, "m").environment, "sky.hdr");
}

TEST(BatchLightingTest, ChoicesDependOnTheSeedAndTheNameOnly) {
    const fs::path dir = "/environments";
    const std::vector<fs::path> files = {dir / "a.hdr", dir / "b.hdr", dir / "sub" / "c.hdr"};
    LightingVariation variation;
    variation.environmentDirectory = dir;
    variation.rotationDegrees = ValueRange(0.0f, 360.0f);
    variation.intensity = ValueRange(0.5f, 1.5f);
    std::map<std::string, int> chosen;
    std::set<float> rotations;
    for (int model = 0; model < 300; ++model) {
        const std::string name = "set/model" + std::to_string(model);
        const ModelLighting lighting = modelLighting(variation, files, {}, 7, name);
        EXPECT_EQ(modelLighting(variation, files, {}, 7, name), lighting) << name;
        ++chosen[lighting.environment];
        EXPECT_EQ(lighting.environmentFile,
                  dir / fs::path(lighting.environment));  // Recorded relative to the folder.
        EXPECT_GE(lighting.rotationDegrees, 0.0f);
        EXPECT_LT(lighting.rotationDegrees, 360.0f);
        EXPECT_FLOAT_EQ(lighting.rotationRadians, lighting.rotationDegrees * float(M_PI) / 180.0f);
        EXPECT_GE(lighting.intensity, 0.5f);
        EXPECT_LE(lighting.intensity, 1.5f);
        rotations.insert(lighting.rotationDegrees);
    }
    // Every file is drawn, about as often as the others.
    ASSERT_EQ(chosen.size(), 3u);
    for (const auto& [name, count] : chosen) {
        EXPECT_GT(count, 60) << name;
    }
    EXPECT_TRUE(chosen.contains("sub/c.hdr"));
    EXPECT_GT(rotations.size(), 290u);
    // Another seed draws otherwise.
    int same = 0;
    for (int model = 0; model < 50; ++model) {
        const std::string name = "set/model" + std::to_string(model);
        same += modelLighting(variation, files, {}, 8, name) ==
                        modelLighting(variation, files, {}, 7, name)
                    ? 1
                    : 0;
    }
    EXPECT_LT(same, 5);
}

TEST(BatchLightingTest, ModelSeedsAreStableAndSpread) {
    EXPECT_EQ(modelSeed(5, ""), 5u);  // No name: the seed itself.
    EXPECT_EQ(modelSeed(5, "a/model"), modelSeed(5, "a/model"));
    EXPECT_NE(modelSeed(5, "a/model"), modelSeed(5, "b/model"));
    EXPECT_NE(modelSeed(5, "a/model"), modelSeed(6, "a/model"));
    // Pinned: these values decide every dataset's views and lighting, on every platform; a
    // change of the hash or the mixing would silently change them all.
    EXPECT_EQ(modelSeed(0, "model"), 13266249493360823179ULL);
    EXPECT_EQ(modelSeed(7, "a/b"), 5046240722416830242ULL);
    std::mt19937_64 a = randomStream(42, RandomStream::Jitter);
    std::mt19937_64 b = randomStream(42, RandomStream::Distance);
    EXPECT_NE(a(), b());
    std::mt19937_64 directions = randomStream(42, RandomStream::Directions);
    EXPECT_EQ(directions(), std::mt19937_64(42)());
    std::mt19937_64 generator(1);
    for (int i = 0; i < 1000; ++i) {
        const double unit = unitInterval(generator);
        EXPECT_GE(unit, 0.0);
        EXPECT_LT(unit, 1.0);
    }
}

}  // namespace
}  // namespace encore::batch
