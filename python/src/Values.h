#pragma once
/// Node outputs as Python values: numbers and text as Python's own, images, maps and
/// particle arrays as read-only NumPy arrays over the value's own memory (zero-copy: the
/// array keeps the value alive), fog volumes as a FogVolume (a sparse description that can
/// write itself as a .vdb), anything else as an opaque Value naming its port type.

#include <string>

#include <pybind11/pybind11.h>

#include "core/Data.h"

namespace cg::python {

void bindValues(pybind11::module_& m);
pybind11::object toPython(const DataPtr& value);
/// A Python value as a value of port type `type` (the inverse of toPython for numbers,
/// text, float arrays, images (height, width, 3 or 4) and cloudgraph.Map2D; other types only
/// as the wrapper toPython made). Throws std::invalid_argument naming `what` and the type.
DataPtr fromPython(const pybind11::handle& value, const std::string& type, const std::string& what);

}  // namespace cg::python
