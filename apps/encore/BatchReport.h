#pragma once

// What `encore batch` prints: the progress line while it runs, and at the end the counts, views
// per second and stage times, per device with several (and with -v), and with -v the upload's
// parts and the GPU's stage timestamps.

#include <cstddef>
#include <string>

#include "encore/batch/Batch.h"

namespace encore::app {

// "12/40 models, 3 failed, 35.2 views/s, ETA 0:00:41"; the ETA from the models attempted in this
// run (those skipped at its start left out).
std::string progressLine(const batch::BatchProgress& progress, std::size_t startSkipped);

// On stdout (a warning on stderr for loads left behind); `threads`: the pool's, which the
// loaders' and encoders' summed times are over.
void printBatchSummary(const batch::BatchSummary& summary, std::size_t threads, bool verbose);

}  // namespace encore::app
