#pragma once
/// The built-in node library, registered explicitly: every node type is listed in Builtin.cc.

namespace cg {

class Registry;

/// Registers the engine's core data types and every built-in node type.
void registerBuiltinNodes(Registry& registry);

}  // namespace cg
