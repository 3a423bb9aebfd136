#pragma once
/// Node declarations as JSON text for cloudgraph.node_types(): ports, parameters with their
/// types, defaults, ranges, units and docs.

#include <string>

#include "core/Registry.h"

namespace cg::python {

std::string nodeTypesJson(const Registry& registry);

}  // namespace cg::python
