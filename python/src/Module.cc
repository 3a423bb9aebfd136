// _cloudgraph: the C++ half of the Python package `cloudgraph` (python/cloudgraph/).

#include <pybind11/pybind11.h>

#include "Bindings.h"

PYBIND11_MODULE(_cloudgraph, m) { cg::python::defineModule(m); }
