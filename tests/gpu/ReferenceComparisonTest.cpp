// Encore against the Khronos glTF Sample Renderer: every model in ../shared/reference is rendered
// under the conditions its JSON states (camera, 320x320, studio.hdr, Khronos PBR Neutral,
// exposure 1, black background, image-based lighting) and compared with the reference PNG by
// SSIM on luminance and mean absolute colour error: per-model floors a little below what was
// measured (docs/reference/README.md lists the numbers), a mean SSIM of at least 0.95 and no
// model below 0.90. With ENCORE_REFERENCE_OUTPUT set, Encore's images and
// Encore | reference | difference sheets are written there.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "TestPaths.h"
#include "encore/image/HdrImage.h"
#include "encore/render/Renderer.h"
#include "image/ImageCompare.h"

namespace encore::render {
namespace {

// The Sample Renderer turns its environment by 90 degrees about +Y before every lookup (its
// default environmentRotation); Encore's --environment-rotation 90 reproduces it (measured: the
// other quarter turns lower the mean SSIM from 0.985 to 0.95, 0.90 and 0.85).
constexpr float kReferenceEnvironmentRotation = 1.5707963f;

struct ReferenceCase {
    std::string name;
    std::filesystem::path model;  // Absolute.
};

// The models `listName` (list.txt, or list-extensions.txt for material extensions) names.
std::vector<ReferenceCase> referenceCases(const char* listName = "list.txt") {
    std::vector<ReferenceCase> cases;
    const auto dir = test::sharedReferenceDir();
    if (!dir) {
        return cases;
    }
    std::ifstream list(*dir / listName);
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

// Measured on lavapipe (docs/reference/README.md), less a margin for drivers that filter or
// rasterise edges differently.
Threshold thresholdFor(const std::string& name) {
    static const std::map<std::string, Threshold> thresholds = {
        {"BoxTextured", {0.965, 3.0}},
        {"Avocado", {0.985, 1.5}},
        {"Duck", {0.985, 1.5}},
        {"NormalTangentTest", {0.955, 3.5}},
        {"MetalRoughSpheresNoTextures", {0.945, 4.5}},
        {"AlphaBlendModeTest", {0.975, 2.0}},
        {"TextureTransformTest", {0.975, 3.0}},
        {"VertexColorTest", {0.965, 4.5}},
        {"MultiUVTest", {0.980, 2.0}},
        {"CesiumMilkTruck", {0.965, 3.0}},
        {"2CylinderEngine", {0.975, 2.0}},
        {"OrientationTest", {0.975, 2.5}},
        {"Fox", {0.980, 1.5}},
        {"BrainStem", {0.975, 2.0}},
        // Material extensions (list-extensions.txt).
        {"TransmissionTest", {0.95, 6.0}},
        {"AttenuationTest", {0.95, 6.0}},
    };
    const auto found = thresholds.find(name);
    return found != thresholds.end() ? found->second : Threshold{0.90, 8.0};
}

// The iridescence and anisotropy references of list-extensions.txt, with their floors: measured
// on lavapipe (docs/reference/README.md), less a margin. Transmission and volume have their own
// test below.
const std::map<std::string, Threshold>& shadedExtensionThresholds() {
    static const std::map<std::string, Threshold> thresholds = {
        // Its left monkey is transmissive: 0.9547 before transmission was shaded, 0.9896 with it.
        {"IridescenceSuzanne", {0.98, 1.5}},
        {"AnisotropyStrengthTest", {0.965, 2.5}},
    };
    return thresholds;
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
    setup.camera =
        Camera::lookAt(vec(camera.at("position")), vec(camera.at("target")),
                       glm::radians(camera.at("yfovDegrees").get<float>()),
                       float(width) / float(height), camera.at("znear").get<float>(), zfar);
    return setup;
}

struct Comparison {
    double ssim = 0.0;
    double colorError = 0.0;
};

// Renders one reference model as the reference did and compares the images.
Comparison compareWithReference(gpu::Context& context,
                                const std::filesystem::path& dir,
                                const ReferenceCase& entry) {
    std::ifstream jsonFile(dir / (entry.name + ".json"));
    const nlohmann::json description = nlohmann::json::parse(jsonFile);
    auto environment = studioEnvironment(dir / description.value("environment", "studio.hdr"));
    EXPECT_NE(environment, nullptr);
    auto scene = scene::loadScene(entry.model);
    EXPECT_TRUE(scene.ok()) << (scene.ok() ? "" : scene.error().message);
    if (!environment || !scene) {
        return {};
    }
    ReferenceSetup setup = referenceSetup(description, environment);
    auto renderer = Renderer::create(context, setup.options);
    EXPECT_TRUE(renderer.ok());
    EXPECT_TRUE(renderer->prepare(*scene, StrategyKind::Bundles).ok());
    renderer->renderFrame(setup.camera);
    auto encore = renderer->readImage();
    auto reference = image::readImage(dir / (entry.name + ".png"));
    EXPECT_TRUE(encore.ok() && reference.ok());
    if (!encore || !reference) {
        return {};
    }
    auto ssim = image::ssimLuminance(*encore, *reference);
    auto error = image::colorError(*encore, *reference);
    EXPECT_TRUE(ssim.ok() && error.ok());
    if (!ssim || !error) {
        return {};
    }
    if (const char* output = std::getenv("ENCORE_REFERENCE_OUTPUT")) {
        const std::filesystem::path out(output);
        std::filesystem::create_directories(out);
        const image::ImageRgba8 difference = image::differenceImage(*encore, *reference, 4.0f);
        const image::ImageRgba8 sheet[] = {*encore, *reference, difference};
        EXPECT_TRUE(image::writePng(out / (entry.name + ".png"), *encore).ok());
        EXPECT_TRUE(
            image::writePng(out / (entry.name + "-compare.png"), image::sideBySide(sheet)).ok());
    }
    EXPECT_TRUE(context.checkNoErrors("rendering " + entry.name).ok());
    return {*ssim, error->meanAbsolute};
}

// One test for the whole set: the target is about the mean as much as about each model.
TEST(ReferenceComparison, EveryModelMatchesTheKhronosSampleRenderer) {
    const auto dir = test::sharedReferenceDir();
    if (!dir) {
        GTEST_SKIP() << "../shared/reference is absent beside the clone: nothing compared";
    }
    ENCORE_REQUIRE_VULKAN(context);
    const auto cases = referenceCases();
    ASSERT_GE(cases.size(), 10u);
    double ssimSum = 0.0;
    double lowest = 1.0;
    for (const ReferenceCase& entry : cases) {
        SCOPED_TRACE(entry.name);
        const Comparison result = compareWithReference(*context, *dir, entry);
        std::printf("reference %-28s SSIM %.4f  mean abs error %.2f\n", entry.name.c_str(),
                    result.ssim, result.colorError);
        const Threshold threshold = thresholdFor(entry.name);
        EXPECT_GE(result.ssim, threshold.minimumSsim);
        EXPECT_LE(result.colorError, threshold.maximumColorError);
        ssimSum += result.ssim;
        lowest = std::min(lowest, result.ssim);
    }
    const double mean = ssimSum / double(cases.size());
    std::printf("reference mean SSIM %.4f, lowest %.4f over %zu models\n", mean, lowest,
                cases.size());
    EXPECT_GE(mean, 0.95);
    EXPECT_GE(lowest, 0.90);
}

// The material-extension models (list-extensions.txt) whose extensions Encore shades.
TEST(ReferenceComparison, ShadedMaterialExtensionsMatchTheKhronosSampleRenderer) {
    const auto dir = test::sharedReferenceDir();
    if (!dir || !std::filesystem::exists(*dir / "list-extensions.txt")) {
        GTEST_SKIP() << "../shared/reference/list-extensions.txt is absent: nothing compared";
    }
    ENCORE_REQUIRE_VULKAN(context);
    std::size_t compared = 0;
    for (const ReferenceCase& entry : referenceCases("list-extensions.txt")) {
        const auto threshold = shadedExtensionThresholds().find(entry.name);
        if (threshold == shadedExtensionThresholds().end()) {
            continue;
        }
        SCOPED_TRACE(entry.name);
        const Comparison result = compareWithReference(*context, *dir, entry);
        std::printf("reference %-28s SSIM %.4f  mean abs error %.2f\n", entry.name.c_str(),
                    result.ssim, result.colorError);
        EXPECT_GE(result.ssim, threshold->second.minimumSsim);
        EXPECT_LE(result.colorError, threshold->second.maximumColorError);
        ++compared;
    }
    EXPECT_EQ(compared, shadedExtensionThresholds().size());
}

// The material-extension references of list-extensions.txt that Encore shades, each held to the
// same target (SSIM 0.95; the floor of thresholdFor).
TEST(ReferenceComparison, ShadedExtensionModelsMatchTheKhronosSampleRenderer) {
    const auto dir = test::sharedReferenceDir();
    if (!dir) {
        GTEST_SKIP() << "../shared/reference is absent beside the clone: nothing compared";
    }
    ENCORE_REQUIRE_VULKAN(context);
    const std::set<std::string> shaded = {"TransmissionTest", "AttenuationTest"};
    std::size_t compared = 0;
    for (const ReferenceCase& entry : referenceCases("list-extensions.txt")) {
        if (!shaded.contains(entry.name)) {
            continue;
        }
        SCOPED_TRACE(entry.name);
        if (!std::filesystem::exists(entry.model)) {
            std::printf("reference %-28s skipped: %s is absent\n", entry.name.c_str(),
                        entry.model.string().c_str());
            continue;
        }
        const Comparison result = compareWithReference(*context, *dir, entry);
        std::printf("reference %-28s SSIM %.4f  mean abs error %.2f\n", entry.name.c_str(),
                    result.ssim, result.colorError);
        const Threshold threshold = thresholdFor(entry.name);
        EXPECT_GE(result.ssim, threshold.minimumSsim);
        EXPECT_LE(result.colorError, threshold.maximumColorError);
        ++compared;
    }
    EXPECT_GT(compared, 0u) << "list-extensions.txt names none of " << shaded.size()
                            << " shaded models";
}

}  // namespace
}  // namespace encore::render
