#pragma once
/// The engine's errors as the Python exceptions of cloudgraph.errors, with the node id and
/// the JSON pointer as attributes.

#include <pybind11/pybind11.h>

namespace cg::python {

void registerErrorTranslator();

}  // namespace cg::python
