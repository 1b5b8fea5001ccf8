#pragma once

// Runs the encore binary built beside the tests (or $ENCORE_BINARY) and captures its output and
// exit code.

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace encore::test {

struct CommandResult {
    int exitCode = -1;
    std::string out;
    std::string err;
};

// `arguments` is appended to the binary's path as it is (quote paths yourself).
CommandResult runEncore(const std::string& arguments);
// The same, run through `prefix` (a shell command line the binary is appended to, such as
// `xvfb-run -a` or `env -u DISPLAY`).
CommandResult runEncoreThrough(const std::string& prefix, const std::string& arguments);

std::string quote(const std::string& text);

// `encore bench ARGUMENTS --json DIR/report.json` and the report it wrote (a discarded value
// when there is none: `command` says why).
struct BenchRun {
    CommandResult command;
    nlohmann::json report;
};
BenchRun runBench(const std::filesystem::path& dir, const std::string& arguments);

}  // namespace encore::test
