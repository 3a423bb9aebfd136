#include "nodes/Builtin.h"

#include "core/Registry.h"
#include "nodes/data/DataTypes.h"
#include "nodes/util/UtilNodes.h"

namespace cg {

void registerBuiltinNodes(Registry& registry)
{
    registerCoreDataTypes(registry);
    registerNodeDataTypes(registry);

    // util/
    registerSourceNodes(registry);
    registerArrayNodes(registry);
    registerIntegrateNode(registry);
    registerStatisticsNode(registry);
    registerWriterNodes(registry);
}

}  // namespace cg
