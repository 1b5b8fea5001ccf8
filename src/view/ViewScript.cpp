#include "view/ViewScript.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <sstream>

#include "core/FileIO.h"

namespace encore::view {

int keyFromName(const std::string& name) {
    if (name.size() == 1) {
        const char c = name[0];
        if (c >= 'a' && c <= 'z') {
            return GLFW_KEY_A + (c - 'a');
        }
        if (c >= 'A' && c <= 'Z') {
            return GLFW_KEY_A + (c - 'A');
        }
        if (c >= '0' && c <= '9') {
            return GLFW_KEY_0 + (c - '0');
        }
        if (c == '[') {
            return GLFW_KEY_LEFT_BRACKET;
        }
        if (c == ']') {
            return GLFW_KEY_RIGHT_BRACKET;
        }
    }
    static const std::pair<const char*, int> kNamed[] = {
        {"space", GLFW_KEY_SPACE}, {"escape", GLFW_KEY_ESCAPE}, {"left", GLFW_KEY_LEFT},
        {"right", GLFW_KEY_RIGHT}, {"up", GLFW_KEY_UP},         {"down", GLFW_KEY_DOWN},
        {"plus", GLFW_KEY_EQUAL},  {"minus", GLFW_KEY_MINUS},
    };
    for (const auto& [named, key] : kNamed) {
        if (name == named) {
            return key;
        }
    }
    return 0;
}

Result<std::vector<ScriptStep>> parseViewScript(const std::string& text,
                                                const std::string& fileName) {
    std::vector<ScriptStep> steps;
    std::istringstream lines(text);
    std::string line;
    int number = 0;
    while (std::getline(lines, line)) {
        ++number;
        if (const auto hash = line.find('#'); hash != std::string::npos) {
            line.erase(hash);
        }
        std::istringstream words(line);
        std::string command;
        if (!(words >> command)) {
            continue;
        }
        auto invalid = [&](const std::string& why) {
            return makeError(ErrorCode::InvalidArgument, fileName + ":" + std::to_string(number) +
                                                             ": " + why + " ('" + line + "').");
        };
        ScriptStep step;
        step.line = number;
        if (command == "frames") {
            step.command = ScriptCommand::Frames;
            long long count = 0;
            if (!(words >> count) || count < 1 || count > 100000) {
                return invalid("frames takes a count from 1 to 100000");
            }
            step.count = std::uint32_t(count);
        } else if (command == "key") {
            step.command = ScriptCommand::Key;
            std::string name;
            words >> name;
            step.key = keyFromName(name);
            if (step.key == 0) {
                return invalid("unknown key '" + name + "'");
            }
        } else if (command == "drag") {
            step.command = ScriptCommand::Drag;
            std::string button;
            if (!(words >> button >> step.x >> step.y) || (button != "left" && button != "right")) {
                return invalid("drag takes left|right DX DY");
            }
            step.key = button == "left" ? GLFW_MOUSE_BUTTON_LEFT : GLFW_MOUSE_BUTTON_RIGHT;
        } else if (command == "scroll") {
            step.command = ScriptCommand::Scroll;
            if (!(words >> step.y)) {
                return invalid("scroll takes DY");
            }
        } else if (command == "resize") {
            step.command = ScriptCommand::Resize;
            long long width = 0;
            long long height = 0;
            if (!(words >> width >> height) || width < 1 || height < 1 || width > 8192 ||
                height > 8192) {
                return invalid("resize takes a width and a height from 1 to 8192");
            }
            step.width = std::uint32_t(width);
            step.height = std::uint32_t(height);
        } else if (command == "drop" || command == "screenshot") {
            step.command = command == "drop" ? ScriptCommand::Drop : ScriptCommand::Screenshot;
            if (!(words >> step.path)) {
                return invalid(command + " takes a path");
            }
            std::string flag;
            if (step.command == ScriptCommand::Screenshot && (words >> flag)) {
                if (flag != "overlay") {
                    return invalid("screenshot takes a path and optionally 'overlay'");
                }
                step.overlay = true;
            }
        } else if (command == "stats") {
            step.command = ScriptCommand::Stats;
        } else if (command == "quit") {
            step.command = ScriptCommand::Quit;
        } else {
            return invalid("unknown command '" + command + "'");
        }
        std::string extra;
        if (words >> extra) {
            return invalid("unexpected '" + extra + "'");
        }
        steps.push_back(std::move(step));
    }
    return steps;
}

Result<std::vector<ScriptStep>> loadViewScript(const std::string& path) {
    ENCORE_TRY_ASSIGN(auto bytes, readFile(path));
    return parseViewScript(std::string(bytes.begin(), bytes.end()), path);
}

}  // namespace encore::view
