#pragma once
/// Node types written in Python (cloudgraph.nodes): the engine side. A Python class is
/// declared to the registry as any node type is; its cook takes the GIL, hands the inputs
/// and parameters to cloudgraph.nodes._cook as Python values and converts what it returns.

#include <string>

namespace cg::python {

/// Registers the node type of `declarationJson` (cloudgraph.nodes.declaration) into
/// sharedRegistry(). The same declaration again is a no-op; a different one under a taken
/// type name, or a declaration the registry refuses, is an InputError naming the type.
void registerPythonNode(const std::string& declarationJson);

}  // namespace cg::python
