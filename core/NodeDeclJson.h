#pragma once
/// Node declarations as JSON: ports, parameters with their types, defaults, ranges, units and
/// docs. What cloudgraph.node_types() and `cloudgraph serve`'s page build their widgets from.

#include <nlohmann/json.hpp>

#include "core/NodeDecl.h"
#include "core/Registry.h"

namespace cg {

nlohmann::json nodeDeclToJson(const NodeDecl& decl);
/// Every node type of `registry`, as an array of nodeDeclToJson.
nlohmann::json nodeTypesToJson(const Registry& registry);

}  // namespace cg
