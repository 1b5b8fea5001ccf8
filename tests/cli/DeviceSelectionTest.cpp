// Choosing the adapter: `encore info` lists them all, `--device N` (or ENCORE_DEVICE) picks one
// and names how many there are when N is past them, and `encore batch --devices` renders on
// several at once with the files one device writes. Lavapipe is one adapter: a list naming it
// twice stands in for two GPUs (two WebGPU devices on it, each with its own device thread).

#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "BatchOutput.h"
#include "CommandRunner.h"
#include "TestFiles.h"
#include "TestPaths.h"

namespace encore::test {
namespace {

namespace fs = std::filesystem;

bool contains(const std::string& text, const std::string& fragment) {
    return text.find(fragment) != std::string::npos;
}

std::set<std::string> lines(const fs::path& path) {
    std::set<std::string> set;
    std::ifstream file(path);
    for (std::string line; std::getline(file, line);) {
        set.insert(line);
    }
    return set;
}

fs::path generate(const fs::path& path, int seed) {
    fs::create_directories(path.parent_path());
    const CommandResult gen =
        runEncore("gen --objects 5 --seed " + std::to_string(seed) + " -o " + quote(path.string()));
    EXPECT_EQ(gen.exitCode, 0) << gen.err;
    return path;
}

TEST(DeviceSelectionTest, InfoListsEveryAdapterAndMarksTheChosenOne) {
    const CommandResult text = runEncore("info");
    ASSERT_EQ(text.exitCode, 0) << text.err;
    EXPECT_TRUE(contains(text.out, "adapters (--device N):\n* 0: ")) << text.out;
    EXPECT_TRUE(contains(text.out, "Vulkan")) << text.out;

    const CommandResult json = runEncore("info --json --device 0");
    ASSERT_EQ(json.exitCode, 0) << json.err;
    const auto report = nlohmann::json::parse(json.out);
    EXPECT_EQ(report["device"], 0);
    ASSERT_GE(report["adapters"].size(), 1u);
    for (std::size_t i = 0; i < report["adapters"].size(); ++i) {
        EXPECT_EQ(report["adapters"][i]["index"], i);
        EXPECT_EQ(report["adapters"][i]["backend"], "Vulkan");
        EXPECT_FALSE(report["adapters"][i]["name"].get<std::string>().empty());
    }
    EXPECT_TRUE(contains(report["adapter"].get<std::string>(),
                         report["adapters"][0]["name"].get<std::string>()));
}

TEST(DeviceSelectionTest, ADevicePastTheAdaptersNamesHowManyThereAre) {
    const CommandResult info = runEncore("info --device 99");
    EXPECT_EQ(info.exitCode, 3) << info.err;
    EXPECT_TRUE(contains(info.err, "error: there is no device 99: this machine has ")) << info.err;
    EXPECT_TRUE(contains(info.err, "`encore info` lists them")) << info.err;

    const fs::path dir = makeTempDir("device-out-of-range");
    const fs::path model = generate(dir / "model.glb", 1);
    const CommandResult render = runEncore("render " + quote(model.string()) + " --device 99 -o " +
                                           quote((dir / "x.png").string()));
    EXPECT_EQ(render.exitCode, 3) << render.err;
    EXPECT_FALSE(fs::exists(dir / "x.png"));

    const CommandResult environment = runEncoreThrough("env ENCORE_DEVICE=99", "info");
    EXPECT_EQ(environment.exitCode, 3) << environment.err;
    const CommandResult notANumber = runEncoreThrough("env ENCORE_DEVICE=first", "info");
    EXPECT_EQ(notANumber.exitCode, 2) << notANumber.err;
    EXPECT_TRUE(contains(notANumber.err, "'first' is not a device index")) << notANumber.err;
    EXPECT_EQ(runEncore("info --device -1").exitCode, 2);
    // --device wins over the environment.
    EXPECT_EQ(runEncoreThrough("env ENCORE_DEVICE=99", "info --device 0").exitCode, 0);
}

TEST(DeviceSelectionTest, RenderingOnDeviceZeroIsTheDefault) {
    const fs::path dir = makeTempDir("device-render");
    const fs::path model = generate(dir / "model.glb", 2);
    const CommandResult plain =
        runEncore("render " + quote(model.string()) + " --width 64 --height 64 -o " +
                  quote((dir / "plain.png").string()));
    ASSERT_EQ(plain.exitCode, 0) << plain.err;
    const CommandResult chosen =
        runEncore("render " + quote(model.string()) + " --width 64 --height 64 --device 0 -o " +
                  quote((dir / "chosen.png").string()));
    ASSERT_EQ(chosen.exitCode, 0) << chosen.err;
    EXPECT_EQ(readBytes(dir / "plain.png"), readBytes(dir / "chosen.png"));
}

TEST(DeviceSelectionTest, BatchOnSeveralDevicesWritesWhatOneDeviceWrites) {
    const fs::path input = makeTempDir("devices-input");
    for (int i = 0; i < 5; ++i) {
        generate(input / ("m" + std::to_string(i) + ".glb"), i + 10);
    }
    std::ofstream(input / "broken.gltf") << "{\"asset\": ";
    const auto batch = [&](const std::string& name, const std::string& extra) {
        const fs::path output = makeTempDir(name);
        const CommandResult run =
            runEncore("batch " + quote(input.string()) + " -o " + quote(output.string()) +
                      " --views 3 --size 48 --quiet " + extra);
        EXPECT_EQ(run.exitCode, 1) << run.out << run.err;  // The broken file.
        EXPECT_TRUE(contains(run.out, "5 rendered, 1 failed, 0 skipped of 6 models")) << run.out;
        EXPECT_FALSE(contains(run.err, "WebGPU")) << run.err;
        return std::make_pair(output, run.out);
    };
    const auto [single, singleOut] = batch("devices-default", "");
    const auto [zero, zeroOut] = batch("devices-zero", "--devices 0");
    const auto [two, twoOut] = batch("devices-two", "--devices 0,0 --renderers 2");
    const auto reference = batchOutputFiles(single);
    ASSERT_EQ(reference.size(), 5u * 5u);  // Three views, metadata.json, transforms.json.
    EXPECT_TRUE(reference == batchOutputFiles(zero));
    EXPECT_TRUE(reference == batchOutputFiles(two));
    EXPECT_EQ(lines(single / "failures.jsonl"), lines(two / "failures.jsonl"));

    // Both devices are reported; together they uploaded every good model once.
    std::size_t models = 0;
    std::istringstream out(twoOut);
    int devices = 0;
    for (std::string line; std::getline(out, line);) {
        if (line.starts_with("device 0 (")) {
            ++devices;
            models += std::stoul(line.substr(line.find("): ") + 3));
        }
    }
    EXPECT_EQ(devices, 2) << twoOut;
    EXPECT_EQ(models, 5u) << twoOut;
    EXPECT_FALSE(contains(singleOut, "device 0 (")) << "one device prints no device lines";
}

TEST(DeviceSelectionTest, BadDeviceListsAreUsageOrAdapterErrors) {
    const fs::path input = makeTempDir("devices-bad");
    generate(input / "m.glb", 3);
    const std::string base =
        "batch " + quote(input.string()) + " -o " + quote((input / "out").string()) + " --quiet ";
    const CommandResult past = runEncore(base + "--devices 0,7");
    EXPECT_EQ(past.exitCode, 3) << past.err;
    EXPECT_TRUE(contains(past.err, "there is no device 7")) << past.err;
    const CommandResult word = runEncore(base + "--devices some");
    EXPECT_EQ(word.exitCode, 2) << word.err;
    EXPECT_TRUE(contains(word.err, "'some' is not a device index")) << word.err;
    const CommandResult both = runEncore(base + "--devices 0 --device 0");
    EXPECT_EQ(both.exitCode, 2) << both.err;
    EXPECT_TRUE(contains(both.err, "exclude each other")) << both.err;
    EXPECT_FALSE(fs::exists(input / "out" / "m"));
}

}  // namespace
}  // namespace encore::test
