#pragma once

// The builders of BatchOptionTable's entries, shared by the files that describe a group of
// options each (BatchOptionTable.cpp and the *OptionEntries.cpp, PassConventionEntries.cpp
// beside it): an entry is made by one builder per form of value and finished by the setters' chain
// (`.excluding({...}).keyword(...)`).

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "batch/BatchOptionTable.h"
#include "batch/OptionNames.h"
#include "encore/batch/Batch.h"
#include "encore/batch/ViewRig.h"
#include "encore/core/Result.h"

namespace encore::batch::optiontable {

using Description = BatchOptionDescription;
inline constexpr float kNoLimit = std::numeric_limits<float>::max();
inline constexpr std::uint32_t kMaxViews = 10'000;
inline constexpr std::uint64_t kAll = std::numeric_limits<std::uint64_t>::max();
inline constexpr std::uint64_t kAll32 = std::numeric_limits<std::uint32_t>::max();

struct Entry {
    Description description;

    Entry&& excluding(std::vector<std::string> names) && {
        description.excludes = std::move(names);
        return std::move(*this);
    }
    Entry&& needing(std::vector<std::string> names) && {
        description.needs = std::move(names);
        return std::move(*this);
    }
    Entry&& shortName(char letter) && {
        description.shortName = letter;
        return std::move(*this);
    }
    Entry&& keyword(std::string name, bool negated = false) && {
        description.keyword = std::move(name);
        description.keywordNegated = negated;
        return std::move(*this);
    }
    Entry&& commandLineOnly() && {
        description.python = false;
        return std::move(*this);
    }
    Entry&& pythonOnly() && {
        description.commandLine = false;
        return std::move(*this);
    }
    Entry&& commandLineGlobal() && {
        description.commandLineGlobal = true;
        return std::move(*this);
    }
};

Entry flag(std::string name, std::string help, std::function<void(BatchOptions&, bool)> set);
Entry wholeNumber(std::string name,
                  std::string valueName,
                  std::string defaultValue,
                  std::string help,
                  std::uint64_t min,
                  std::uint64_t max,
                  std::function<void(BatchOptions&, std::uint64_t)> set);
Entry number(std::string name,
             std::string valueName,
             std::string defaultValue,
             std::string help,
             float min,
             float max,
             std::function<void(BatchOptions&, float)> set);
Entry range(std::string name,
            std::string valueName,
            std::string defaultValue,
            std::string help,
            std::function<void(BatchOptions&, ValueRange)> set);
Entry text(std::string name,
           OptionForm form,
           std::string valueName,
           std::string help,
           std::function<Result<void>(BatchOptions&, std::string_view, std::string_view)> apply);

template <class Enum>
Entry named(std::string name,
            std::string defaultValue,
            std::string help,
            NameTable<Enum> table,
            std::function<void(BatchOptions&, Enum)> set) {
    Description d;
    d.name = std::move(name);
    d.form = OptionForm::Text;
    d.defaultValue = std::move(defaultValue);
    d.help = std::move(help);
    d.choices = namesOf(table);
    d.apply = [set, table](BatchOptions& options, std::string_view value,
                           std::string_view shown) -> Result<void> {
        ENCORE_TRY_ASSIGN(const Enum parsed, parseNamed(table, value, shown));
        set(options, parsed);
        return Result<void>{};
    };
    return {std::move(d)};
}

// The groups, each in the order its options are applied.
void addCameraOptions(std::vector<Entry>& entries);          // CameraOptionEntries.cpp
void addPassConventionOptions(std::vector<Entry>& entries);  // PassConventionEntries.cpp
void addShadingOptions(std::vector<Entry>& entries);         // ShadingOptionEntries.cpp

}  // namespace encore::batch::optiontable
