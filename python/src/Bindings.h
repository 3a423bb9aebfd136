#pragma once
/// The contents of the module cloudgraph._cloudgraph, defined once for its two homes: the
/// Python extension (Module.cc) and the interpreter the CLI embeds for --python-nodes
/// (EmbeddedPython.cc).

#include <pybind11/pybind11.h>

namespace cg::python {

void defineModule(pybind11::module_& m);

}  // namespace cg::python
