#pragma once
/// Node outputs as Python values: numbers and text as Python's own, images, maps and
/// particle arrays as read-only NumPy arrays over the value's own memory (zero-copy: the
/// array keeps the value alive), fog volumes as a FogVolume (a sparse description that can
/// write itself as a .vdb), anything else as an opaque Value naming its port type.

#include <pybind11/pybind11.h>

#include "core/Data.h"

namespace cg::python {

void bindValues(pybind11::module_& m);
pybind11::object toPython(const DataPtr& value);

}  // namespace cg::python
