#include "CommandRunner.h"

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "TestFiles.h"
#include "TestPaths.h"

namespace encore::test {

std::string quote(const std::string& text) {
    std::string quoted = "'";
    for (char c : text) {
        quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    }
    return quoted + "'";
}

BenchRun runBench(const std::filesystem::path& dir, const std::string& arguments) {
    const auto json = dir / "report.json";
    BenchRun run;
    run.command = runEncore("bench " + arguments + " --json " + quote(json.string()));
    std::ifstream file(json);
    run.report = nlohmann::json::parse(file, nullptr, false);
    return run;
}

CommandResult runEncore(const std::string& arguments) {
    return runEncoreThrough("", arguments);
}

CommandResult runEncoreThrough(const std::string& prefix, const std::string& arguments) {
    const char* overridden = std::getenv("ENCORE_BINARY");
    const std::string binary = overridden ? overridden : ENCORE_BINARY_PATH;
    CommandResult result;
    const auto dir = makeTempDir("command");
    const auto out = dir / "stdout";
    const auto err = dir / "stderr";
    const std::string command = prefix + " " + quote(binary) + " " + arguments + " >" +
                                quote(out.string()) + " 2>" + quote(err.string()) + " </dev/null";
    const int status = std::system(command.c_str());
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    result.out = readBytes(out);
    result.err = readBytes(err);
    return result;
}

}  // namespace encore::test
