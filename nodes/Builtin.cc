#include "nodes/Builtin.h"

#include "core/Registry.h"
#include "nodes/util/UtilNodes.h"

namespace cg {

void registerBuiltinNodes(Registry& registry)
{
    registerCoreDataTypes(registry);

    // util/
    registerSourceNodes(registry);
    registerArrayNodes(registry);
    registerIntegrateNode(registry);
    registerStatisticsNode(registry);
    registerWriterNodes(registry);
}

}  // namespace cg
