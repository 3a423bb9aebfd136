#pragma once
/// Registers the port data types of the node library (beyond the engine's own).

namespace cg {

class Registry;

void registerNodeDataTypes(Registry& registry);

}  // namespace cg
