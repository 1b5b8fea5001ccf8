#include "GpuTestSupport.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>

#include <nlohmann/json.hpp>

#include "TestPaths.h"
#include "core/Log.h"
#include "render/visibility/VisibilityFeatures.h"

namespace encore::test {

gpu::Context* vulkanContext() {
    static std::unique_ptr<gpu::Context> context = [] {
        // WebGPU errors are also recorded by the context; printing them helps a failing test.
        setLogSink([](LogLevel level, std::string_view message) {
            if (level == LogLevel::Error) {
                std::fprintf(stderr, "[webgpu] %.*s\n", int(message.size()), message.data());
            }
        });
        gpu::ContextOptions options;
        render::requestVisibilityFeatures(options);
        auto created = gpu::Context::create(options);
        if (!created) {
            std::fprintf(stderr, "%s\n", created.error().message.c_str());
            return std::unique_ptr<gpu::Context>();
        }
        std::fprintf(stderr, "adapter: %s\n", created->adapterDescription().summary().c_str());
        return std::make_unique<gpu::Context>(std::move(*created));
    }();
    return context.get();
}

Rgba pixelAt(const image::ImageRgba8& image, std::uint32_t x, std::uint32_t y) {
    const std::uint8_t* p = image.pixel(x, y);
    return {p[0], p[1], p[2], p[3]};
}

std::string describe(const Rgba& color) {
    return "(" + std::to_string(color[0]) + ", " + std::to_string(color[1]) + ", " +
           std::to_string(color[2]) + ", " + std::to_string(color[3]) + ")";
}

bool shadesMaterials(render::StrategyKind kind) {
    return kind >= render::StrategyKind::Materials;  // StrategyKind lists them in this order.
}

int channelDistance(const Rgba& a, const Rgba& b) {
    int distance = 0;
    for (int c = 0; c < 4; ++c) {
        distance = std::max(distance, std::abs(int(a[c]) - int(b[c])));
    }
    return distance;
}

double coveredFraction(const image::ImageRgba8& image, const Rgba& background, int tolerance) {
    std::size_t covered = 0;
    for (std::uint32_t y = 0; y < image.height; ++y) {
        for (std::uint32_t x = 0; x < image.width; ++x) {
            covered += channelDistance(pixelAt(image, x, y), background) > tolerance;
        }
    }
    return double(covered) / double(std::size_t(image.width) * image.height);
}

std::size_t differingPixels(const image::ImageRgba8& a, const image::ImageRgba8& b, int tolerance) {
    if (a.width != b.width || a.height != b.height) {
        return std::size_t(-1);
    }
    std::size_t count = 0;
    for (std::uint32_t y = 0; y < a.height; ++y) {
        for (std::uint32_t x = 0; x < a.width; ++x) {
            count += channelDistance(pixelAt(a, x, y), pixelAt(b, x, y)) > tolerance;
        }
    }
    return count;
}

std::uint8_t linearToSrgb8(double linear) {
    linear = std::clamp(linear, 0.0, 1.0);
    const double encoded =
        linear <= 0.0031308 ? linear * 12.92 : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
    return static_cast<std::uint8_t>(std::lround(encoded * 255.0));
}

std::string strategyTestName(render::StrategyKind kind) {
    std::string name(render::strategyName(kind));
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
}

std::vector<render::StrategyChoice> everyStrategyChoice() {
    std::vector<render::StrategyChoice> choices;
    for (render::StrategyKind kind : render::allStrategies()) {
        choices.push_back({kind, false});
        if (!render::isBundledKind(kind)) {
            choices.push_back({kind, true});
        }
    }
    return choices;
}

std::string ModelVariant::testName() const {
    std::string name = model + "_" + variant;
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
}

void PrintTo(const ModelVariant& variant, std::ostream* out) {
    *out << variant.model << " (" << variant.variant << ")";
}

std::vector<ModelVariant> sharedModelVariants() {
    std::vector<ModelVariant> variants;
    const auto dir = sharedModelsDir();
    if (!dir) {
        return variants;
    }
    std::ifstream file(*dir / "index.json");
    const auto index = nlohmann::json::parse(file, nullptr, false);
    if (!index.is_array()) {
        return variants;
    }
    for (const auto& model : index) {
        for (const auto& [variant, entry] : model.at("variants").items()) {
            variants.push_back({model.at("name").get<std::string>(), variant,
                                (*dir / entry.at("file").get<std::string>()).string()});
        }
    }
    return variants;
}

scene::SceneData generatedScene(const scene::GeneratorOptions& options) {
    auto glb = scene::generateSceneGlb(options);
    EXPECT_TRUE(glb.ok()) << glb.error().message;
    if (!glb.ok()) {
        return {};
    }
    auto scene = scene::loadSceneFromMemory(*glb, {}, "generated.glb");
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene.ok() ? std::move(*scene) : scene::SceneData{};
}

void writeGeneratedScene(const std::filesystem::path& path,
                         std::uint32_t objects,
                         std::uint32_t seed) {
    scene::GeneratorOptions generator;
    generator.objectCount = objects;
    generator.meshCount = 3;
    generator.materialCount = 2;
    generator.seed = seed;
    generator.textures = true;
    auto glb = scene::generateSceneGlb(generator);
    ASSERT_TRUE(glb.ok()) << glb.error().message;
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(glb->data()), std::streamsize(glb->size()));
}

}  // namespace encore::test
