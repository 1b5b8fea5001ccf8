#pragma once

// batch()'s keyword arguments as the batch's options (batch/BatchOptionTable.h): each value turned
// into the text `encore batch` would be given, so that both fronts parse and check it in one
// place. An unknown keyword is a TypeError naming the nearest one; a value of the wrong type a
// TypeError; a value the option does not take a ValueError when the options are applied.

#include <pybind11/pybind11.h>

#include <vector>

#include "batch/BatchOptionTable.h"

namespace encore::python {

namespace py = pybind11;

std::vector<batch::GivenOption> givenBatchOptions(const py::kwargs& keywords);

// The keywords besides the table's that batch() takes: passes=.
std::string batchKeywordsDocstring();

}  // namespace encore::python
