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
    EXPECT_FALSE(modelFinished(folder, {.views = 2}));
    std::ofstream(viewImagePath(folder, 0)) << "x";
    std::ofstream(viewImagePath(folder, 1)) << "x";
    std::ofstream(folder / kTransformsFileName) << "{}";
    // Output of a version that wrote no metadata.json is not finished: it is rendered again.
    EXPECT_FALSE(modelFinished(folder, {.views = 2}));
    std::ofstream(folder / "metadata.json") << "{}";
    EXPECT_TRUE(modelFinished(folder, {.views = 2}));
    EXPECT_FALSE(modelFinished(folder, {.views = 3}));  // A third view is missing.
    EXPECT_EQ(modelFiles(folder, {.views = 2}),
              (std::vector<fs::path>{folder / "000.png", folder / "001.png",
                                     folder / "metadata.json", folder / "transforms.json"}));
}

TEST(ModelOutputTest, NormalImagesBelongToTheModelWhenAskedFor) {
    const fs::path folder = test::makeTempDir("model-output-normals");
    EXPECT_EQ(viewImagePath(folder, 3, ViewImage::Normal), folder / "003_normal.png");
    EXPECT_EQ(viewImagePath(folder, 3, ViewImage::Depth), folder / "003_depth.png");
    EXPECT_EQ(modelFiles(folder, {.views = 1, .extras = {.normals = true, .depth = true}}),
              (std::vector<fs::path>{folder / "000.png", folder / "000_normal.png",
                                     folder / "000_depth.png", folder / "metadata.json",
                                     folder / "transforms.json"}));
    std::ofstream(folder / "000.png") << "x";
    std::ofstream(folder / "metadata.json") << "{}";
    std::ofstream(folder / kTransformsFileName) << "{}";
    EXPECT_TRUE(modelFinished(folder, {.views = 1}));
    EXPECT_FALSE(modelFinished(folder, {.views = 1, .extras = {.normals = true}}));
}

// Every pass is one more file per view, in the order extraPasses lists them; EXR depth and the
// HDR image end in .exr.
TEST(ModelOutputTest, EveryPassIsAFileOfTheModel) {
    const fs::path folder = test::makeTempDir("model-output-passes");
    const ExtraImages all{.normals = true,
                          .depth = true,
                          .albedo = true,
                          .material = true,
                          .segmentation = true,
                          .hdr = true,
                          .depthFormat = DepthFormat::Exr};
    EXPECT_EQ(all.perView(), 7u);
    EXPECT_EQ(
        modelFiles(folder, {.views = 1, .extras = all}),
        (std::vector<fs::path>{
            folder / "000.png", folder / "000_normal.png", folder / "000_depth.exr",
            folder / "000_albedo.png", folder / "000_material.png", folder / "000_segmentation.png",
            folder / "000_hdr.exr", folder / "metadata.json", folder / "transforms.json"}));
    EXPECT_EQ(viewImagePath(folder, 2, ViewImage::Depth), folder / "002_depth.png");
    EXPECT_EQ(extraPasses({.albedo = true, .hdr = true}),
              (std::vector<ViewImage>{ViewImage::Albedo, ViewImage::Hdr}));
}

TEST(ModelOutputTest, TheObjaverseLayoutAddsACameraMatrixPerView) {
    const fs::path folder = test::makeTempDir("model-output-objaverse");
    BatchOptions options;
    options.views.views = 2;
    EXPECT_FALSE(modelFileSet(options).cameraMatrices);
    options.layout = OutputLayout::Objaverse;
    const ModelFileSet set = modelFileSet(options);
    EXPECT_TRUE(set.cameraMatrices);
    EXPECT_EQ(set.views, 2u);
    EXPECT_EQ(cameraMatrixPath(folder, 7), folder / "007.npy");
    EXPECT_EQ(modelFiles(folder, set),
              (std::vector<fs::path>{folder / "000.png", folder / "000.npy", folder / "001.png",
                                     folder / "001.npy", folder / "metadata.json",
                                     folder / "transforms.json"}));
    for (const fs::path& file : modelFiles(folder, {.views = 2})) {
        std::ofstream(file) << "x";
    }
    EXPECT_FALSE(modelFinished(folder, set));  // The matrices are missing.
    std::ofstream(folder / "000.npy") << "x";
    std::ofstream(folder / "001.npy") << "x";
    EXPECT_TRUE(modelFinished(folder, set));
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
