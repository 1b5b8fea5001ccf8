#include "shaders/ShaderComposer.h"

#include <cctype>
#include <vector>

#include "shaders/EmbeddedFiles.h"

namespace encore::shaders {
namespace {

std::string_view trim(std::string_view text) {
    const auto first = text.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) {
        return {};
    }
    const auto last = text.find_last_not_of(" \t\r");
    return text.substr(first, last - first + 1);
}

bool isIdentifier(std::string_view text) {
    if (text.empty() || std::isdigit(static_cast<unsigned char>(text[0]))) {
        return false;
    }
    for (char c : text) {
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') {
            return false;
        }
    }
    return true;
}

// One open #if block.
struct Conditional {
    bool parentActive;  // Whether the enclosing block emits lines.
    bool branchTaken;   // Whether an earlier branch of this block was active.
    bool active;        // Whether the current branch emits lines.
    bool sawElse;
};

class Composer {
  public:
    Composer(const std::set<std::string, std::less<>>& flags, const FileLookup& lookup)
        : mFlags(flags), mLookup(lookup) {}

    Result<void> compose(std::string_view fileName) {
        if (!mIncluded.insert(std::string(fileName)).second) {
            return {};  // Already included: like #pragma once.
        }
        const auto text = mLookup(fileName);
        if (!text) {
            return makeError(ErrorCode::InvalidArgument,
                             "Shader file '" + std::string(fileName) + "' does not exist.");
        }
        std::vector<Conditional> stack;
        std::size_t lineNumber = 0;
        std::size_t position = 0;
        while (position <= text->size()) {
            auto end = text->find('\n', position);
            if (end == std::string_view::npos) {
                end = text->size();
            }
            const std::string_view line = text->substr(position, end - position);
            position = end + 1;
            ++lineNumber;
            const bool active = stack.empty() || stack.back().active;
            const std::string_view trimmed = trim(line);
            if (trimmed.starts_with('#')) {
                ENCORE_TRY(directive(fileName, lineNumber, trimmed, active, stack));
            } else if (active) {
                mOutput.append(line);
                mOutput.push_back('\n');
            }
            if (end == text->size()) {
                break;
            }
        }
        if (!stack.empty()) {
            return error(fileName, lineNumber, "#if without #endif");
        }
        return {};
    }

    std::string takeOutput() { return std::move(mOutput); }

  private:
    static Error error(std::string_view file, std::size_t line, const std::string& what) {
        return makeError(ErrorCode::InvalidArgument, "Shader '" + std::string(file) + "' line " +
                                                         std::to_string(line) + ": " + what + ".");
    }

    Result<bool> evaluate(std::string_view file, std::size_t line, std::string_view condition) {
        bool negate = false;
        if (condition.starts_with('!')) {
            negate = true;
            condition = trim(condition.substr(1));
        }
        if (!isIdentifier(condition)) {
            return error(file, line,
                         "condition '" + std::string(condition) + "' is not a flag name");
        }
        return mFlags.contains(condition) != negate;
    }

    Result<void> directive(std::string_view file,
                           std::size_t line,
                           std::string_view text,
                           bool active,
                           std::vector<Conditional>& stack) {
        const auto space = text.find_first_of(" \t");
        const std::string_view name = text.substr(0, space);
        const std::string_view argument =
            space == std::string_view::npos ? std::string_view{} : trim(text.substr(space));
        if (name == "#include") {
            if (argument.size() < 2 || argument.front() != '"' || argument.back() != '"') {
                return error(file, line, "#include needs a quoted file name");
            }
            if (active) {
                return compose(argument.substr(1, argument.size() - 2));
            }
            return {};
        }
        if (name == "#if") {
            ENCORE_TRY_ASSIGN(const bool value, evaluate(file, line, argument));
            stack.push_back({active, active && value, active && value, false});
            return {};
        }
        if (name == "#elif" || name == "#else" || name == "#endif") {
            if (stack.empty()) {
                return error(file, line, std::string(name) + " without #if");
            }
            Conditional& top = stack.back();
            if (name == "#endif") {
                stack.pop_back();
                return {};
            }
            if (top.sawElse) {
                return error(file, line, std::string(name) + " after #else");
            }
            bool condition = true;
            if (name == "#elif") {
                ENCORE_TRY_ASSIGN(condition, evaluate(file, line, argument));
            } else {
                top.sawElse = true;
            }
            top.active = top.parentActive && !top.branchTaken && condition;
            top.branchTaken = top.branchTaken || top.active;
            return {};
        }
        return error(file, line, "unknown directive '" + std::string(name) + "'");
    }

    const std::set<std::string, std::less<>>& mFlags;
    const FileLookup& mLookup;
    std::set<std::string, std::less<>> mIncluded;
    std::string mOutput;
};

}  // namespace

Result<std::string> composeShader(std::string_view fileName,
                                  const std::set<std::string, std::less<>>& flags,
                                  const FileLookup& lookup) {
    Composer composer(flags, lookup);
    ENCORE_TRY(composer.compose(fileName));
    return composer.takeOutput();
}

Result<std::string> composeEmbeddedShader(std::string_view fileName,
                                          const std::set<std::string, std::less<>>& flags) {
    const FileLookup lookup = [](std::string_view name) -> std::optional<std::string_view> {
        for (const auto& file : wgslFiles()) {
            if (file.name == name) {
                return file.contents;
            }
        }
        return std::nullopt;
    };
    return composeShader(fileName, flags, lookup);
}

}  // namespace encore::shaders
