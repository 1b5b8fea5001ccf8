#pragma once

// OUT/failures.jsonl: one JSON object per line for each model a batch could not finish,
//   {"file": "<the model's path>", "stage": "load", "error": "<message>"}
// where the message is the one `encore render` prints after "error: ". Stages: load (parse and
// decode), upload (preparing the GPU scene), render (drawing and reading back), write (encoding
// and writing the files). Lines are written whole and flushed as they happen, so the log is
// complete up to the moment a run stops. The log also keeps its entries, so that a caller that
// runs several batches into one folder (encore.dask) can gather them and write one file.
// Safe to use from several threads.

#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "encore/batch/Batch.h"  // Failure
#include "encore/core/Result.h"

namespace encore::batch {

class FailureLog {
  public:
    // Creates or empties the log: a run lists the failures of the models it tried.
    static Result<FailureLog> create(const std::filesystem::path& path);
    // A log that writes no file and only keeps its entries.
    static FailureLog inMemory();

    void record(const std::filesystem::path& file,
                const std::string& stage,
                const std::string& message);
    std::size_t count() const;
    std::vector<Failure> entries() const;

  private:
    struct State;
    std::shared_ptr<State> mState;  // Shared: the log is moved out of create().
};

}  // namespace encore::batch
