#include "BatchOptionsCli.h"

#include <cstdio>
#include <vector>

#include "batch/BatchPresets.h"

namespace encore::app {

void BatchOptionsCli::addTo(CLI::App& command) {
    for (const batch::BatchOptionDescription& description : batch::batchOptionDescriptions()) {
        if (!description.commandLine || description.commandLineGlobal) {
            continue;
        }
        Entry& entry = mEntries.emplace_back();
        entry.description = &description;
        const std::string names =
            (description.shortName ? "-" + std::string(1, description.shortName) + "," : "") +
            "--" + description.name;
        if (description.form == batch::OptionForm::Flag) {
            entry.option = command.add_flag(names, entry.on, description.help);
            continue;
        }
        entry.option = command.add_option(names, entry.value, description.help);
        if (!description.choices.empty()) {
            entry.option->type_name("{" + [&] {
                std::string list;
                for (const std::string& choice : description.choices) {
                    list += (list.empty() ? "" : ",") + choice;
                }
                return list;
            }() + "}");
        } else {
            entry.option->type_name(description.valueName);
        }
        if (!description.defaultValue.empty()) {
            entry.option->default_str(description.defaultValue);
        }
        if (description.name == "preset") {
            entry.option->type_name("{" + [&] {
                std::string list;
                for (const std::string& choice : description.choices) {
                    list += choice + ",";
                }
                return list;
            }() + "list}");
            // `--preset list` prints the presets and their sources, as --help prints the
            // options: a validator runs before CLI11 asks for the input and output.
            entry.option->each([](const std::string& value) {
                if (value == "list") {
                    std::fputs(batch::presetListing().c_str(), stdout);
                    throw CLI::Success();
                }
            });
        }
    }
    // What each option excludes, for --help and CLI11's checks. What an option needs is checked
    // by applyBatchOptions, which also counts the options a --preset gives.
    for (Entry& entry : mEntries) {
        for (const std::string& name : entry.description->excludes) {
            for (Entry& other : mEntries) {
                if (other.description->name == name) {
                    entry.option->excludes(other.option);
                }
            }
        }
    }
}

Result<void> BatchOptionsCli::applyTo(batch::BatchOptions& options,
                                      const GlobalOptions& global) const {
    std::vector<batch::GivenOption> given;
    for (const Entry& entry : mEntries) {
        if (entry.option->count() == 0) {
            continue;
        }
        given.push_back({entry.description, entry.description->form == batch::OptionForm::Flag
                                                ? std::string(entry.on ? "true" : "false")
                                                : entry.value});
    }
    if (global.allowUrisOutside) {
        given.push_back(
            {batch::findBatchOption("allow-uris-outside", batch::OptionFront::CommandLine),
             "true"});
    }
    return batch::applyBatchOptions(options, given, batch::OptionFront::CommandLine);
}

}  // namespace encore::app
