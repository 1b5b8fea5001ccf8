#pragma once

// Runs the encore binary built beside the tests (or $ENCORE_BINARY) and captures its output and
// exit code.

#include <string>

namespace encore::test {

struct CommandResult {
    int exitCode = -1;
    std::string out;
    std::string err;
};

// `arguments` is appended to the binary's path as it is (quote paths yourself).
CommandResult runEncore(const std::string& arguments);

std::string quote(const std::string& text);

}  // namespace encore::test
