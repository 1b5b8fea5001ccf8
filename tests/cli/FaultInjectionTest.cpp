// Faults the commands must survive with a documented exit code, injected through test hooks
// once the scene is prepared (apps/encore/Commands.h): a lost device (exit code 4) and the GPU
// running out of memory (exit code 5). CTest labels gpu and sanitize: they also run under
// AddressSanitizer (make test-sanitize).

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "CommandRunner.h"
#include "TestPaths.h"

namespace encore::test {
namespace {

// A device lost while rendering or benchmarking stops the command with exit code 4 and a message
// naming the loss (the test hook makes Dawn lose the device once the scene is prepared).
TEST(FaultInjectionTest, ADeviceLossStopsRenderAndBenchWithExitCodeFour) {
    const auto dir = makeTempDir("device-loss");
    const auto scene = dir / "scene.glb";
    ASSERT_EQ(runEncore("gen --objects 8 -o " + quote(scene.string())).exitCode, 0);
    ::setenv("ENCORE_TEST_FORCE_DEVICE_LOSS", "1", 1);
    const auto render =
        runEncore("render " + quote(scene.string()) + " -o " + quote((dir / "lost.png").string()));
    const auto bench = runEncore("bench --objects 8 --frames 2 --warmup 0 --strategy bundles");
    ::unsetenv("ENCORE_TEST_FORCE_DEVICE_LOSS");
    EXPECT_EQ(render.exitCode, 4) << render.err;
    EXPECT_NE(render.err.find("the GPU device was lost"), std::string::npos) << render.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "lost.png"));
    EXPECT_EQ(bench.exitCode, 4) << bench.err;
    EXPECT_NE(bench.err.find("the GPU device was lost"), std::string::npos) << bench.err;
}

// The GPU running out of memory stops render and bench with exit code 5 and a message saying so
// (the test hook makes Dawn report an out-of-memory error once the scene is prepared, as it does
// when an allocation fails).
TEST(FaultInjectionTest, RunningOutOfGpuMemoryStopsRenderAndBenchWithExitCodeFive) {
    const auto dir = makeTempDir("out-of-memory");
    const auto scene = dir / "scene.glb";
    ASSERT_EQ(runEncore("gen --objects 8 -o " + quote(scene.string())).exitCode, 0);
    ::setenv("ENCORE_TEST_INJECT_OUT_OF_MEMORY", "1", 1);
    const auto render =
        runEncore("render " + quote(scene.string()) + " -o " + quote((dir / "oom.png").string()));
    const auto bench = runEncore("bench --objects 8 --frames 2 --warmup 0 --strategy bundles");
    ::unsetenv("ENCORE_TEST_INJECT_OUT_OF_MEMORY");
    EXPECT_EQ(render.exitCode, 5) << render.err;
    EXPECT_NE(render.err.find("the GPU ran out of memory (injected by "
                              "ENCORE_TEST_INJECT_OUT_OF_MEMORY)"),
              std::string::npos)
        << render.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "oom.png"));
    EXPECT_EQ(bench.exitCode, 5) << bench.err;
    EXPECT_NE(bench.err.find("the GPU ran out of memory"), std::string::npos) << bench.err;
}

}  // namespace
}  // namespace encore::test
