#pragma once
/// cloudgraph.write_image: an image array to a PNG or EXR file, by WriteImage's own code.

#include <pybind11/pybind11.h>

namespace cg::python {

void bindImageFiles(pybind11::module_& m);

}  // namespace cg::python
