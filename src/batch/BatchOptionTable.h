#pragma once

// Every option of a batch described once: its name, the form of its value, its default, its
// help, the values it takes, the options it excludes or needs, the fronts that take it, and how
// its value sets BatchOptions. `encore batch`'s options and help (apps/encore/BatchOptionsCli),
// Python's batch() keywords and docstring (python/BatchKeywords) and docs/batch.md's option table
// are all built from this table: a new option is one entry here plus its use.
//
// Every front hands the values over as text, as the command line writes them (Python's keywords
// turned into that text first), so each value is parsed and checked in one place and its error
// names the option as the user's front spells it ("--views" or "views").

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "encore/batch/Batch.h"
#include "encore/core/Result.h"

namespace encore::batch {

// The form of an option's value, for fronts that take typed values (Python); the command line
// takes every value as text.
enum class OptionForm {
    Flag,         // On or off (Python: a bool).
    WholeNumber,  // Python: an int.
    Number,       // Python: an int or a float.
    Range,        // A number or MIN:MAX, drawn from (Python: a number or a (min, max) pair).
    ImageSize,    // W or WxH (Python: an int or a (width, height) pair).
    ByteSize,     // 1GiB, 500MB, 1000000 (Python: an int or such a str).
    NumberList,   // A,B,... (Python: a sequence of numbers).
    Text,         // A name or a path (Python: a str or an os.PathLike; variant also an int).
};

// The fronts an option belongs to.
enum class OptionFront : unsigned {
    CommandLine = 1,
    Python = 2,
};

struct BatchOptionDescription {
    // The command line's long name without its dashes ("camera-distribution"); Python's keyword
    // is the same with underscores unless `keyword` says otherwise.
    std::string name;
    OptionForm form = OptionForm::Text;
    // What the help calls the value ("N", "DEG|MIN:MAX"); empty for flags and names (choices).
    std::string valueName;
    // The default as the command line writes it; empty: none (the help says what happens then).
    std::string defaultValue;
    std::string help;
    std::vector<std::string> choices;   // The names it takes, when a list.
    std::vector<std::string> excludes;  // Options (names) it cannot be given with.
    std::vector<std::string> needs;     // Options it needs given (a flag: on).
    char shortName = 0;                 // -j; 0: none.
    bool commandLine = true;            // `encore batch --name`.
    bool python = true;                 // batch(name=...).
    // On the command line before the subcommand (`encore --allow-uris-outside batch`).
    bool commandLineGlobal = false;
    std::string keyword;          // Python's keyword when not the name with underscores.
    bool keywordNegated = false;  // Python's keyword is the flag's opposite (normalize=True).
    // Sets `options` from the value (a flag's: "true" or "false"); errors name it as `shown`.
    std::function<
        Result<void>(BatchOptions& options, std::string_view value, std::string_view shown)>
        apply;

    std::string pythonKeyword() const;
    // "--name", or Python's keyword.
    std::string shownName(OptionFront front) const;
    bool takenBy(OptionFront front) const {
        return front == OptionFront::CommandLine ? commandLine : python;
    }
};

std::span<const BatchOptionDescription> batchOptionDescriptions();

// The option of that command-line name (without dashes) or Python keyword; nullptr if none.
const BatchOptionDescription* findBatchOption(std::string_view name, OptionFront front);

// The names `front` spells its options with, for "did you mean" answers.
std::vector<std::string> batchOptionNames(OptionFront front);

struct GivenOption {
    const BatchOptionDescription* option = nullptr;
    std::string value;  // As the command line writes it.
};

// Checks what the given options exclude and need of each other, then applies them in the
// table's order over `options` (the defaults, or what the caller set first). InvalidArgument for
// a value an option does not take; the errors name the options as `front` spells them.
Result<void> applyBatchOptions(BatchOptions& options,
                               std::span<const GivenOption> given,
                               OptionFront front);

// docs/batch.md's table of the options (Markdown), and Python's docstring lines for them.
std::string batchOptionsMarkdown();
std::string batchOptionsDocstring();

}  // namespace encore::batch
