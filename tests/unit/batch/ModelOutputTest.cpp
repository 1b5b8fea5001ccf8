#include <gtest/gtest.h>

#include <fstream>

#include "TestPaths.h"
#include "batch/ModelOutput.h"

namespace encore::batch {
namespace {

namespace fs = std::filesystem;

TEST(ModelOutputTest, FinishedOnlyWithEveryFile) {
    const fs::path folder = test::makeTempDir("model-output") / "a" / "model";
    fs::create_directories(folder);
    EXPECT_FALSE(modelFinished(folder, 2));
    std::ofstream(viewImagePath(folder, 0)) << "x";
    std::ofstream(viewImagePath(folder, 1)) << "x";
    EXPECT_FALSE(modelFinished(folder, 2));  // No transforms.json yet.
    std::ofstream(folder / kTransformsFileName) << "{}";
    EXPECT_TRUE(modelFinished(folder, 2));
    EXPECT_FALSE(modelFinished(folder, 3));  // A third view is missing.
    EXPECT_EQ(modelFiles(folder, 2), (std::vector<fs::path>{folder / "000.png", folder / "001.png",
                                                            folder / "transforms.json"}));
}

TEST(ModelOutputTest, NormalImagesBelongToTheModelWhenAskedFor) {
    const fs::path folder = test::makeTempDir("model-output-normals");
    EXPECT_EQ(viewImagePath(folder, 3, ViewImage::Normal), folder / "003_normal.png");
    EXPECT_EQ(viewImagePath(folder, 3, ViewImage::Depth), folder / "003_depth.png");
    EXPECT_EQ(modelFiles(folder, 1, {.normals = true, .depth = true}),
              (std::vector<fs::path>{folder / "000.png", folder / "000_normal.png",
                                     folder / "000_depth.png", folder / "transforms.json"}));
    std::ofstream(folder / "000.png") << "x";
    std::ofstream(folder / kTransformsFileName) << "{}";
    EXPECT_TRUE(modelFinished(folder, 1));
    EXPECT_FALSE(modelFinished(folder, 1, {.normals = true}));
}

TEST(ModelOutputTest, RemovesOnlyPartialFiles) {
    const fs::path folder = test::makeTempDir("model-output-partial");
    std::ofstream(folder / "000.png") << "x";
    std::ofstream(folder / "001.png.part") << "x";
    std::ofstream(folder / "transforms.json.part") << "x";
    removePartialFiles(folder);
    EXPECT_TRUE(fs::exists(folder / "000.png"));
    EXPECT_FALSE(fs::exists(folder / "001.png.part"));
    EXPECT_FALSE(fs::exists(folder / "transforms.json.part"));
    removePartialFiles(folder / "absent");  // Nothing to do, no error.
}

TEST(ModelOutputTest, FolderFollowsTheName) {
    EXPECT_EQ(modelFolder("/out", "a/b/model"), fs::path("/out/a/b/model"));
}

}  // namespace
}  // namespace encore::batch
