#pragma once

// OUT/failures.jsonl: one JSON object per line for each model a batch could not finish,
//   {"file": "<the model's path>", "stage": "load", "error": "<message>"}
// where the message is the one `encore render` prints after "error: ". Stages: load (parse and
// decode), upload (preparing the GPU scene), render (drawing and reading back), write (encoding
// and writing the files). Lines are written whole and flushed as they happen, so the log is
// complete up to the moment a run stops. Safe to use from several threads.

#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>

#include "encore/core/Result.h"

namespace encore::batch {

class FailureLog {
  public:
    // Creates or empties the log: a run lists the failures of the models it tried.
    static Result<FailureLog> create(const std::filesystem::path& path);

    void record(const std::filesystem::path& file,
                const std::string& stage,
                const std::string& message);
    std::size_t count() const;

  private:
    struct State;
    std::shared_ptr<State> mState;  // Shared: the log is moved out of create().
};

}  // namespace encore::batch
