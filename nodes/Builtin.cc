#include "nodes/Builtin.h"

#include "core/Registry.h"
#include "nodes/atmosphere/AtmosphereNodes.h"
#include "nodes/data/DataTypes.h"
#include "nodes/io/IoNodes.h"
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

    // atmosphere/
    registerAtmosphereNode(registry);
    registerNoiseMapNode(registry);
    registerVapourEmitterNode(registry);
    registerThermalIntegratorNode(registry);
    registerCondensationNode(registry);

    // io/
    registerWriteMapNode(registry);
    registerWriteParticlesNode(registry);
}

}  // namespace cg
