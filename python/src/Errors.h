#pragma once
/// The engine's errors as the Python exceptions of cloudgraph.errors, with the node id and
/// the JSON pointer as attributes.

#include <pybind11/pybind11.h>

#include "core/Error.h"

namespace cg::python {

void registerErrorTranslator();

/// The Python exception `e` holds, with its traceback, as Python prints it. Needs the GIL.
std::string pythonTraceback(pybind11::error_already_set& e);

}  // namespace cg::python
