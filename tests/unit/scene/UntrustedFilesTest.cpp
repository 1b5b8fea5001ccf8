// Files from untrusted collections (issue 51): a model's external uris resolve only inside the
// folder that holds it (absolute paths, `..` escapes, percent-encoded ones and symbolic links
// that lead out are refused with the uri named; a buffer fails the model, an image is drawn as
// missing), unless LoadOptions::allowUrisOutside; only regular files are read (a FIFO would block
// the loader for ever); the decoded bytes a model holds stay under LoadOptions::maxModelBytes;
// JSON with more values than a glTF asset needs is refused before it is parsed.

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "SceneTestUtils.h"
#include "TestPaths.h"
#include "core/FileIO.h"

namespace encore::scene {
namespace {

namespace fs = std::filesystem;
using testing::expectError;
using testing::triangleBuilder;

// ROOT/model/model.gltf reading its triangle from buffer uri `uri`; the bytes lie in
// ROOT/secret.bin (outside the model's folder) and ROOT/model/inside.bin, and a link
// ROOT/model/link.bin leads to the secret.
struct Layout {
    fs::path root;
    fs::path model;

    Result<SceneData> loadWithBuffer(const std::string& uri, LoadOptions options = {}) const {
        rewrite([&](nlohmann::json& json) { json["buffers"][0]["uri"] = uri; });
        return loadScene(model, options);
    }
    Result<SceneData> loadWithImage(const std::string& uri, LoadOptions options = {}) const {
        rewrite([&](nlohmann::json& json) {
            json["buffers"][0]["uri"] = "inside.bin";
            json["images"] = nlohmann::json::array({{{"uri", uri}}});
            json["textures"] = nlohmann::json::array({{{"source", 0}}});
            json["materials"] = nlohmann::json::array(
                {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
            json["meshes"][0]["primitives"][0]["material"] = 0;
        });
        return loadScene(model, options);
    }

  private:
    template <typename Edit>
    void rewrite(Edit edit) const {
        const auto bytes = readFile(model);
        ASSERT_TRUE(bytes.ok());
        nlohmann::json json = nlohmann::json::parse(bytes->begin(), bytes->end());
        edit(json);
        std::ofstream(model) << json.dump();
    }
};

Layout makeLayout(const std::string& name) {
    Layout layout;
    layout.root = test::makeTempDir(name);
    const fs::path folder = layout.root / "model";
    fs::create_directories(folder / "sub");
    layout.model =
        triangleBuilder().writeGltf(folder, "model", test::GltfBuilder::BufferMode::ExternalBin);
    fs::copy_file(folder / "model.bin", folder / "inside.bin");
    fs::copy_file(folder / "model.bin", layout.root / "secret.bin");
    fs::create_symlink(layout.root / "secret.bin", folder / "link.bin");
    fs::create_symlink(layout.root, folder / "up");  // A link to the folder above.
    fs::create_symlink(folder / "inside.bin", folder / "sub" / "near.bin");  // Inside.
    return layout;
}

TEST(UntrustedFilesTest, BuffersOutsideTheModelsFolderAreRefused) {
    const Layout layout = makeLayout("untrusted-buffers");
    const std::string secret = (layout.root / "secret.bin").string();
    for (const std::string& uri :
         {secret, std::string("../secret.bin"), std::string("%2E%2E/secret.bin"),
          std::string("sub/../../secret.bin"), std::string("link.bin"),
          std::string("up/secret.bin"), std::string("up/model/../secret.bin")}) {
        SCOPED_TRACE(uri);
        expectError(layout.loadWithBuffer(uri), ErrorCode::FileUnreadable,
                    {layout.model.string(), "buffer 0", "is outside the model's folder",
                     "--allow-uris-outside"});
    }
    expectError(layout.loadWithBuffer("file:///etc/passwd"), ErrorCode::Unsupported,
                {"buffer 0", "not a relative file reference"});
    // Inside, however written: through `..` that stays inside, a link to a file inside.
    for (const std::string& uri : {std::string("inside.bin"), std::string("sub/../inside.bin"),
                                   std::string("./sub/near.bin"), std::string("%69nside.bin")}) {
        auto scene = layout.loadWithBuffer(uri);
        EXPECT_TRUE(scene.ok()) << uri << ": " << scene.error().message;
    }
    // Trusted trees may read anywhere.
    LoadOptions trusted;
    trusted.allowUrisOutside = true;
    for (const std::string& uri : {secret, std::string("../secret.bin"), std::string("link.bin")}) {
        auto scene = layout.loadWithBuffer(uri, trusted);
        ASSERT_TRUE(scene.ok()) << uri << ": " << scene.error().message;
        EXPECT_EQ(scene->drawnTriangleCount(), 1u);
    }
}

TEST(UntrustedFilesTest, ImagesOutsideTheModelsFolderAreDrawnAsMissing) {
    const Layout layout = makeLayout("untrusted-images");
    ASSERT_TRUE(writeFile(layout.root / "secret.png", std::vector<std::uint8_t>{1, 2, 3}).ok());
    auto scene = layout.loadWithImage("../secret.png");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->images.size(), 1u);
    EXPECT_TRUE(scene->images[0].rgba8.empty());
    ASSERT_EQ(scene->warnings.size(), 1u);
    EXPECT_NE(scene->warnings[0].find("image 0 ('../secret.png') cannot be read"),
              std::string::npos)
        << scene->warnings[0];
    EXPECT_NE(scene->warnings[0].find("is outside the model's folder"), std::string::npos)
        << scene->warnings[0];
    LoadOptions strict;
    strict.strict = true;
    expectError(layout.loadWithImage("../secret.png", strict), ErrorCode::FileUnreadable,
                {"is outside the model's folder"});
}

TEST(UntrustedFilesTest, AFifoIsRefusedAtOnce) {
    const Layout layout = makeLayout("untrusted-fifo");
    ASSERT_EQ(::mkfifo((layout.model.parent_path() / "pipe.bin").c_str(), 0600), 0);
    // Without the check the load would block in open() for ever: the test would not end.
    expectError(layout.loadWithBuffer("pipe.bin"), ErrorCode::FileUnreadable,
                {"buffer 0", "is a FIFO, not a regular file"});
    auto scene = layout.loadWithImage("pipe.bin");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene->images[0].rgba8.empty());
}

TEST(UntrustedFilesTest, AModelHoldingMoreThanItsLimitFails) {
    const Layout layout = makeLayout("untrusted-bytes");
    LoadOptions limited;
    limited.maxModelBytes = 8;  // The triangle's buffer holds 36 bytes.
    expectError(layout.loadWithBuffer("inside.bin", limited), ErrorCode::LimitExceeded,
                {"holds 36 bytes", "after reading its buffers", "limit of 8 bytes"});
    limited.maxModelBytes = 36;
    EXPECT_TRUE(layout.loadWithBuffer("inside.bin", limited).ok());
}

TEST(UntrustedFilesTest, JsonWithMoreValuesThanAnAssetNeedsIsRefusedBeforeParsing) {
    std::string text = R"({"asset": {"version": "2.0"}, "extras": [0)";
    text.reserve(text.size() + 2 * 10'000'001 + 2);
    for (int i = 0; i < 10'000'001; ++i) {
        text += ",0";
    }
    text += "]}";
    expectError(testing::loadText(text), ErrorCode::LimitExceeded,
                {"test.gltf", "more than 10000000 values"});
}

TEST(UntrustedFilesTest, MoreElementsOfAKindThanTheLimitAreRefused) {
    std::string nodes = "{}";
    nodes.reserve(3 * 1'000'001);
    for (int i = 0; i < 1'000'000; ++i) {
        nodes += ",{}";
    }
    expectError(testing::loadText(R"({"asset": {"version": "2.0"}, "nodes": [)" + nodes + "]}"),
                ErrorCode::LimitExceeded, {"1000001 nodes", "limit of 1000000"});
    std::string primitives = R"({"attributes": {}})";
    // 500,001 meshes of two primitives each: within the limit as meshes, past it as primitives.
    const std::string twoEach = R"({"primitives": [)" + primitives + "," + primitives + "]}";
    std::string doubled = twoEach;
    for (int i = 0; i < 500'000; ++i) {
        doubled += "," + twoEach;
    }
    expectError(testing::loadText(R"({"asset": {"version": "2.0"}, "meshes": [)" + doubled + "]}"),
                ErrorCode::LimitExceeded, {"1000002 primitives"});
}

}  // namespace
}  // namespace encore::scene
