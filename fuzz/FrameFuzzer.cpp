// The frame fuzzer: the mutations of encore_fuzz_numbers (NumberMutator.h) carried through the
// whole renderer — load, Renderer::prepare with a real strategy and one rendered frame on the
// Vulkan adapter (lavapipe here) — in the sanitizer build (ASan + UBSan, every report fatal).
// libFuzzer needs clang, and Debian's clang 14 cannot compile Dawn's webgpu_cpp.h, so this
// driver is built by g++ and has no coverage feedback: iteration i mutates seed i (mod the seed
// count) afresh, with random choices drawn from (--seed, i) alone, so that any iteration can be
// replayed by itself (--first i --iterations 1).
//
// An input passes when the loader refuses it with an error that names it, when prepare refuses
// it with an error of its own (a limit, an unsupported feature; not a WebGPU error), or when its
// frame renders and reads back without any WebGPU error. Anything else (a WebGPU validation or
// out-of-memory error, a lost device, an error that does not name the input) is a finding: the
// input is saved to --findings and the run fails. A sanitizer report or a crash ends the
// process at once; each input is written to --findings before it runs, so the one that caused
// it is there (running.gltf or running.glb, and running.txt saying which it is).
// docs/fuzzing.md has the runs.

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "NumberMutator.h"
#include "core/Log.h"
#include "encore/gpu/Context.h"
#include "encore/image/HdrImage.h"
#include "encore/render/Renderer.h"
#include "encore/scene/SceneData.h"

namespace encore::fuzz {
namespace {

namespace fs = std::filesystem;
using Random = std::mt19937;

constexpr std::uint32_t kTargetSize = 64;
// Room for what the number mutator writes (a number can grow to 1e300 written out in full).
constexpr std::size_t kMutationHeadroom = 64 * 1024;
constexpr std::uint64_t kProgressInterval = 1000;

struct Options {
    std::uint64_t iterations = 1000;
    std::uint64_t first = 0;
    std::uint32_t seed = 1;
    bool replay = false;  // Run each input as it is, with every strategy.
    fs::path findings = ".";
    std::vector<fs::path> inputs;
};

struct Seed {
    std::string name;
    std::vector<std::uint8_t> bytes;
};

// What one input did.
enum class Outcome { LoaderRefused, PrepareRefused, Rendered, Finding };

void printUsage() {
    std::fprintf(
        stderr,
        "usage: encore_frame_fuzzer [--iterations N] [--first I] [--seed S] [--findings DIR]\n"
        "                           [--replay] SEED...\n"
        "SEED: .gltf or .glb files, or directories of them (fuzz/make-corpus.sh writes one).\n"
        "Each iteration I (I = first, ..., first + N - 1) mutates the I-th seed that loads\n"
        "(modulo their count) with the random choices of (S, I), and runs it through load,\n"
        "prepare with a random strategy and animation evaluation, and one frame. --replay\n"
        "runs each file unmutated with every strategy and evaluation instead. Findings,\n"
        "and the input running, are written to DIR (default: the current directory).\n");
}

bool parseNumber(const char* text, std::uint64_t& value) {
    char* end = nullptr;
    value = std::strtoull(text, &end, 10);
    return end != text && *end == '\0';
}

bool parseOptions(int argc, char** argv, Options& options) {
    for (int i = 1; i < argc; ++i) {
        const std::string_view argument = argv[i];
        const bool hasValue = i + 1 < argc;
        std::uint64_t number = 0;
        if (argument == "--iterations" && hasValue && parseNumber(argv[++i], number)) {
            options.iterations = number;
        } else if (argument == "--first" && hasValue && parseNumber(argv[++i], number)) {
            options.first = number;
        } else if (argument == "--seed" && hasValue && parseNumber(argv[++i], number)) {
            options.seed = std::uint32_t(number);
        } else if (argument == "--findings" && hasValue) {
            options.findings = argv[++i];
        } else if (argument == "--replay") {
            options.replay = true;
        } else if (!argument.starts_with("--")) {
            options.inputs.emplace_back(argument);
        } else {
            std::fprintf(stderr, "encore_frame_fuzzer: bad argument '%s'.\n", argv[i]);
            return false;
        }
    }
    return !options.inputs.empty();
}

// The files given, and the files of the directories given (sorted: the order is part of what
// makes a run repeatable).
std::vector<Seed> readSeeds(const std::vector<fs::path>& inputs) {
    std::vector<fs::path> files;
    for (const fs::path& input : inputs) {
        if (fs::is_directory(input)) {
            std::vector<fs::path> listed;
            for (const auto& entry : fs::directory_iterator(input)) {
                if (entry.is_regular_file()) {
                    listed.push_back(entry.path());
                }
            }
            std::sort(listed.begin(), listed.end());
            files.insert(files.end(), listed.begin(), listed.end());
        } else {
            files.push_back(input);
        }
    }
    std::vector<Seed> seeds;
    for (const fs::path& file : files) {
        std::ifstream stream(file, std::ios::binary);
        if (!stream) {
            std::fprintf(stderr, "encore_frame_fuzzer: cannot read '%s'.\n", file.c_str());
            continue;
        }
        seeds.push_back({file.filename().string(),
                         std::vector<std::uint8_t>(std::istreambuf_iterator<char>(stream), {})});
    }
    return seeds;
}

// For what the number mutator leaves alone (one input in sixteen, and inputs that are not glTF
// JSON or GLB): one to four byte-level changes, as libFuzzer's LLVMFuzzerMutate would make.
void mutateBytes(std::vector<std::uint8_t>& bytes, Random& random) {
    static constexpr std::uint8_t kInteresting[] = {0,   1,   0x7F, 0x80, 0xFF, '0', '9',
                                                    '-', '.', 'e',  '"',  ',',  '[', '}'};
    const unsigned steps = 1 + random() % 4;
    for (unsigned step = 0; step < steps && !bytes.empty(); ++step) {
        const std::size_t at = random() % bytes.size();
        switch (random() % 4) {
            case 0:
                bytes[at] = std::uint8_t(random());
                break;
            case 1:
                bytes[at] = kInteresting[random() % std::size(kInteresting)];
                break;
            case 2: {  // Erase a few bytes.
                const std::size_t count =
                    std::min<std::size_t>(1 + random() % 8, bytes.size() - at);
                bytes.erase(bytes.begin() + std::ptrdiff_t(at),
                            bytes.begin() + std::ptrdiff_t(at + count));
                break;
            }
            default: {  // Repeat a few bytes.
                const std::size_t count =
                    std::min<std::size_t>(1 + random() % 8, bytes.size() - at);
                const std::vector<std::uint8_t> copy(bytes.begin() + std::ptrdiff_t(at),
                                                     bytes.begin() + std::ptrdiff_t(at + count));
                bytes.insert(bytes.begin() + std::ptrdiff_t(at), copy.begin(), copy.end());
                break;
            }
        }
    }
}

// One round of mutation, or (one time in six) two or three, as libFuzzer stacks them.
std::vector<std::uint8_t> mutate(const std::vector<std::uint8_t>& seed, Random& random) {
    std::vector<std::uint8_t> bytes = seed;
    const unsigned rounds = 1 + (random() % 4 == 0 ? random() % 3 : 0);
    for (unsigned round = 0; round < rounds; ++round) {
        const std::size_t size = bytes.size();
        bytes.resize(size + kMutationHeadroom);
        const std::size_t mutated = mutateNumbers(bytes.data(), size, bytes.size(), random());
        bytes.resize(mutated != 0 ? mutated : size);
        if (mutated == 0) {
            mutateBytes(bytes, random);
        }
    }
    return bytes;
}

std::string extensionOf(const std::string& name) {
    const std::string extension = fs::path(name).extension().string();
    return extension == ".glb" || extension == ".gltf" ? extension : ".gltf";
}

fs::path saveInput(const fs::path& directory,
                   const std::vector<std::uint8_t>& bytes,
                   const std::string& fileName) {
    std::error_code ignored;
    fs::create_directories(directory, ignored);
    const fs::path path = directory / fileName;
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    return path;
}

void removeRunningInput(const fs::path& directory) {
    std::error_code ignored;
    for (const char* name : {"running.gltf", "running.glb", "running.txt"}) {
        fs::remove(directory / name, ignored);
    }
}

// Writes the input about to run, and what it is, where they survive a sanitizer report.
void saveRunningInput(const fs::path& directory,
                      const std::vector<std::uint8_t>& bytes,
                      const std::string& extension,
                      const std::string& description) {
    removeRunningInput(directory);  // The last input's, which may have the other extension.
    saveInput(directory, bytes, "running" + extension);
    std::ofstream(directory / "running.txt") << description << '\n';
}

bool isGpuError(const Error& error) {
    return error.code == ErrorCode::ValidationError || error.code == ErrorCode::OutOfMemory ||
           error.code == ErrorCode::DeviceError;
}

// The display name of an input (.gltf or .glb): the loader's errors must name it.
std::string inputName(const std::string& extension) {
    return "fuzz-input" + extension;
}

Result<scene::SceneData> loadInput(const std::vector<std::uint8_t>& bytes,
                                   const std::string& displayName) {
    scene::LoadOptions options;
    options.decodeImages = true;
    // External uris resolve against a directory that does not exist (as in the libFuzzer
    // targets): the seeds are self-contained, and inputs cannot reach the repository's files.
    return scene::loadSceneFromMemory(bytes, "/nonexistent/encore-fuzz", displayName, options);
}

// One input of the run: a seed mutated (or as it is, with --replay) and the strategy to draw it.
struct Input {
    std::vector<std::uint8_t> bytes;
    render::StrategyChoice choice;
    render::AnimationEvaluation animation = render::AnimationEvaluation::Cpu;
    std::string extension;    // .gltf or .glb, as its seed
    std::string description;  // "... (gen-attributes.glb mutated, naive, cpu animation)"
    std::string fileName;     // its name once saved as a finding
};

// Load, prepare and one frame. `finding` says what went wrong when the outcome is a finding.
Outcome runInput(gpu::Context& context,
                 render::Renderer& renderer,
                 const Input& input,
                 std::string& finding) {
    const std::string displayName = inputName(input.extension);
    auto scene = loadInput(input.bytes, displayName);
    if (!scene) {
        if (scene.error().message.find(displayName) == std::string::npos) {
            finding = "the loader's error does not name the input: " + scene.error().message;
            return Outcome::Finding;
        }
        return Outcome::LoaderRefused;
    }
    // Every path ends with the scene released: the renderer must not outlive what it drew.
    struct ReleaseScene {
        render::Renderer& renderer;
        ~ReleaseScene() { renderer.releaseScene(); }
    } release{renderer};
    auto refusedOrFinding = [&](const Error& error, const char* step) {
        if (isGpuError(error) || error.message.empty() || context.errorCount() != 0) {
            finding = std::string(step) + " failed (" + std::string(errorCodeName(error.code)) +
                      "): " + error.message;
            return Outcome::Finding;
        }
        return Outcome::PrepareRefused;
    };
    if (auto evaluation = renderer.setAnimationEvaluation(input.animation); !evaluation) {
        return refusedOrFinding(evaluation.error(), "setAnimationEvaluation");
    }
    if (auto prepared = renderer.prepare(*scene, input.choice.kind, input.choice.bundle);
        !prepared) {
        return refusedOrFinding(prepared.error(), "prepare");
    }
    // Animated scenes also upload a pose other than the rest pose.
    if (!scene->animations.empty()) {
        if (auto animated = renderer.setAnimationTime(0.5); !animated) {
            return refusedOrFinding(animated.error(), "setAnimationTime");
        }
    }
    const render::Camera camera =
        render::Camera::framing(scene->bounds, renderer.target().aspect());
    renderer.renderFrame(camera);
    auto image = renderer.readImage();
    if (!image) {
        finding = "reading the frame back failed: " + image.error().message;
        return Outcome::Finding;
    }
    if (image->width != kTargetSize || image->height != kTargetSize) {
        finding = "the frame read back has the wrong size";
        return Outcome::Finding;
    }
    if (auto clean = context.checkNoErrors("the frame"); !clean) {
        finding = clean.error().message;
        return Outcome::Finding;
    }
    return Outcome::Rendered;
}

struct Totals {
    std::uint64_t inputs = 0;
    std::uint64_t loaderRefused = 0;
    std::uint64_t prepareRefused = 0;
    std::uint64_t rendered = 0;
    std::uint64_t findings = 0;
    double slowestSeconds = 0.0;
    std::string slowest;
};

Result<render::Renderer> createRenderer(gpu::Context& context) {
    render::RendererOptions options;
    options.target = {kTargetSize, kTargetSize, 1};
    // A small environment, built in well under a second on lavapipe.
    options.environmentImage = std::make_shared<image::HdrImage>(image::makeStudioEnvironment(256));
    options.environmentOptions.specularSize = 64;
    options.environmentOptions.irradianceSize = 16;
    options.environmentOptions.lutSize = 64;
    options.environmentOptions.specularSamples = 64;
    options.environmentOptions.irradianceSamples = 128;
    // Each shader variant is compiled once for the whole run, not once per input.
    options.keepPipelines = true;
    return render::Renderer::create(context, options);
}

// The seeds worth mutating: those the loader accepts as they are. The others (bad inputs, .gltf
// files whose buffers are external files) almost never reach the GPU once mutated, and the
// libFuzzer targets run their mutations ten times faster.
std::vector<Seed> loadableSeeds(std::vector<Seed> seeds) {
    std::erase_if(seeds, [](const Seed& seed) {
        return !loadInput(seed.bytes, inputName(extensionOf(seed.name)));
    });
    return seeds;
}

constexpr render::AnimationEvaluation kEvaluations[] = {render::AnimationEvaluation::Cpu,
                                                        render::AnimationEvaluation::Gpu};

// "bundles, gpu animation"
std::string setting(const Input& input) {
    return render::strategyChoiceName(input.choice) + ", " +
           std::string(render::animationEvaluationName(input.animation)) + " animation";
}

// "bundles-gpu", for the file names of findings.
std::string fileSetting(const Input& input) {
    return render::strategyChoiceName(input.choice) + "-" +
           std::string(render::animationEvaluationName(input.animation));
}

// Step `step` of the run: with random choices drawn from (--seed, iteration) alone, so that
// `--first I --iterations 1` makes iteration I again.
Input makeInput(const Options& options,
                const std::vector<Seed>& seeds,
                const std::vector<render::StrategyChoice>& choices,
                std::uint64_t step) {
    Input input;
    if (options.replay) {
        // Every strategy, with animation on the CPU and on the GPU.
        const Seed& seed = seeds[step / (choices.size() * 2)];
        input.bytes = seed.bytes;
        input.choice = choices[step / 2 % choices.size()];
        input.animation = kEvaluations[step % 2];
        input.extension = extensionOf(seed.name);
        input.description = seed.name + " (" + setting(input) + ")";
        input.fileName =
            fs::path(seed.name).stem().string() + "-" + fileSetting(input) + input.extension;
        return input;
    }
    const std::uint64_t iteration = options.first + step;
    const Seed& seed = seeds[iteration % seeds.size()];
    std::seed_seq seedSequence{options.seed, std::uint32_t(iteration),
                               std::uint32_t(iteration >> 32)};
    Random random(seedSequence);
    input.bytes = mutate(seed.bytes, random);
    input.choice = choices[random() % choices.size()];
    input.animation = kEvaluations[random() % 2];
    input.extension = extensionOf(seed.name);
    input.description = "iteration " + std::to_string(iteration) + " of seed " +
                        std::to_string(options.seed) + " (" + seed.name + " mutated, " +
                        setting(input) + ")";
    input.fileName = "frame-fuzz-seed" + std::to_string(options.seed) + "-iteration" +
                     std::to_string(iteration) + "-" + fileSetting(input) + input.extension;
    return input;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Totals so far (every kProgressInterval inputs of a long run) and at the end.
void printSummary(const Options& options, const Totals& totals, double seconds) {
    std::printf(
        "encore_frame_fuzzer: %llu inputs in %.1f s (%.1f per second%s): %llu refused by the "
        "loader, %llu refused by prepare, %llu frames rendered, %llu findings; slowest %.2f s "
        "(%s)\n",
        static_cast<unsigned long long>(totals.inputs), seconds,
        double(totals.inputs) / std::max(seconds, 1e-9),
        options.replay ? ", replayed"
                       : (", seed " + std::to_string(options.seed) + ", iterations " +
                          std::to_string(options.first) + " to " +
                          std::to_string(options.first + totals.inputs - 1))
                             .c_str(),
        static_cast<unsigned long long>(totals.loaderRefused),
        static_cast<unsigned long long>(totals.prepareRefused),
        static_cast<unsigned long long>(totals.rendered),
        static_cast<unsigned long long>(totals.findings), totals.slowestSeconds,
        totals.slowest.c_str());
    std::fflush(stdout);
}

int run(const Options& options) {
    const std::vector<Seed> files = readSeeds(options.inputs);
    const std::vector<Seed> seeds = options.replay ? files : loadableSeeds(files);
    if (seeds.empty()) {
        std::fprintf(stderr, "encore_frame_fuzzer: no seed file%s.\n",
                     files.empty() ? "" : " that loads");
        return 2;
    }
    // WebGPU errors are recorded by the context and reported with the finding; warnings of
    // the loader (thousands of them) are dropped.
    setLogSink([](LogLevel level, std::string_view message) {
        if (level == LogLevel::Error) {
            std::fprintf(stderr, "[webgpu] %.*s\n", int(message.size()), message.data());
        }
    });
    auto context = gpu::Context::create();
    if (!context) {
        std::fprintf(stderr, "encore_frame_fuzzer: %s\n", context.error().message.c_str());
        return 2;
    }
    auto renderer = createRenderer(*context);
    if (!renderer) {
        std::fprintf(stderr, "encore_frame_fuzzer: %s\n", renderer.error().message.c_str());
        return 2;
    }
    std::vector<render::StrategyChoice> kinds;
    for (render::StrategyKind kind : render::allStrategies()) {
        kinds.push_back({kind, false});
    }
    const std::vector<render::StrategyChoice> choices = render::withBundlingAxis(kinds, true);
#if defined(__SANITIZE_ADDRESS__)
    const char* sanitizers = "ASan + UBSan";
#else
    const char* sanitizers = "no sanitizer";
#endif
    std::printf(
        "encore_frame_fuzzer: %zu seeds (of %zu files), %s, adapter %s; each input is "
        "written to %s/running.* before it runs\n",
        seeds.size(), files.size(), sanitizers, context->adapterDescription().summary().c_str(),
        options.findings.c_str());
    std::fflush(stdout);

    Totals totals;
    const auto start = std::chrono::steady_clock::now();
    const std::uint64_t count =
        options.replay ? seeds.size() * choices.size() * 2 : options.iterations;
    for (std::uint64_t step = 0; step < count; ++step) {
        const Input input = makeInput(options, seeds, choices, step);
        saveRunningInput(options.findings, input.bytes, input.extension, input.description);
        std::string finding;
        const auto inputStart = std::chrono::steady_clock::now();
        const Outcome outcome = runInput(*context, *renderer, input, finding);
        const double seconds = secondsSince(inputStart);
        ++totals.inputs;
        if (seconds > totals.slowestSeconds) {
            totals.slowestSeconds = seconds;
            totals.slowest = input.description;
        }
        totals.loaderRefused += outcome == Outcome::LoaderRefused;
        totals.prepareRefused += outcome == Outcome::PrepareRefused;
        totals.rendered += outcome == Outcome::Rendered;
        if (outcome == Outcome::Finding) {
            ++totals.findings;
            const fs::path path = saveInput(options.findings, input.bytes, input.fileName);
            std::fprintf(stderr, "encore_frame_fuzzer: FINDING in %s: %s\n  input: %s\n",
                         input.description.c_str(), finding.c_str(), path.c_str());
            context->takeErrors();
        }
        if (totals.inputs % kProgressInterval == 0 && totals.inputs < count) {
            printSummary(options, totals, secondsSince(start));
        }
        if (context->deviceLost()) {
            std::fprintf(stderr, "encore_frame_fuzzer: the device was lost in %s; stopping.\n",
                         input.description.c_str());
            ++totals.findings;
            break;
        }
    }
    removeRunningInput(options.findings);
    printSummary(options, totals, secondsSince(start));
    if (totals.findings != 0) {
        return 1;
    }
    // A run in which nothing reaches the GPU tests nothing (the seeds are missing, or the
    // mutations broke): fail rather than pass.
    if (totals.inputs >= 50 && totals.rendered == 0) {
        std::fprintf(stderr, "encore_frame_fuzzer: no input reached a frame.\n");
        return 1;
    }
    return 0;
}

}  // namespace
}  // namespace encore::fuzz

int main(int argc, char** argv) {
    encore::fuzz::Options options;
    if (!encore::fuzz::parseOptions(argc, argv, options)) {
        encore::fuzz::printUsage();
        return 2;
    }
    return encore::fuzz::run(options);
}
