#pragma once

// `encore batch`'s options, added to the command from the batch's one description of its options
// (batch/BatchOptionTable.h): the names, value names, defaults and help that `--help` prints and
// what they exclude and need; once parsed, the values given are checked and applied by the
// description (errors exit 2 as CLI11's do).

#include <CLI/CLI.hpp>

#include <deque>
#include <string>

#include "Commands.h"
#include "batch/BatchOptionTable.h"
#include "encore/batch/Batch.h"
#include "encore/core/Result.h"

namespace encore::app {

class BatchOptionsCli {
  public:
    // Adds every option of the command line's front to `command` (its global ones are the
    // program's, in GlobalOptions).
    void addTo(CLI::App& command);

    // The options given (and the global ones that are batch options), applied in the table's
    // order over `options`.
    Result<void> applyTo(batch::BatchOptions& options, const GlobalOptions& global) const;

  private:
    struct Entry {
        const batch::BatchOptionDescription* description = nullptr;
        CLI::Option* option = nullptr;
        std::string value;
        bool on = false;  // A flag's.
    };
    std::deque<Entry> mEntries;  // CLI11 keeps references to the values.
};

}  // namespace encore::app
