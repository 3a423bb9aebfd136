#pragma once
/// Every node type and port data type the engine knows. Built-in nodes are added by an
/// explicit registerBuiltinNodes(); plugins add theirs through their entry point.

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/Data.h"
#include "core/NodeDecl.h"

namespace cg {

class Registry {
public:
    /// Adds a node type; throws std::invalid_argument on a duplicate name, an undeclared
    /// port type, or a declaration that breaks its own rules (default out of range...).
    void addNode(NodeDecl decl);
    /// Adds a port data type; re-adding an identical name is an error.
    void addDataType(DataTypeInfo info);

    const NodeDecl* findNode(const std::string& type) const;
    const DataTypeInfo* findDataType(const std::string& name) const;
    std::vector<const NodeDecl*> nodes() const;          ///< sorted by type name
    std::vector<const DataTypeInfo*> dataTypes() const;  ///< sorted by name

private:
    std::map<std::string, std::unique_ptr<NodeDecl>> mNodes;
    std::map<std::string, DataTypeInfo> mDataTypes;
};

/// Registers the engine's own data types (Float, Int, FloatArray, Text).
void registerCoreDataTypes(Registry& registry);

}  // namespace cg
