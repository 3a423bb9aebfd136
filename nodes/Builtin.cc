#include "nodes/Builtin.h"

#include "core/Registry.h"
#include "nodes/atmosphere/AtmosphereNodes.h"
#include "nodes/data/DataTypes.h"
#include "nodes/fluid/FluidNodes.h"
#include "nodes/io/IoNodes.h"
#include "nodes/mapping/MappingNodes.h"
#include "nodes/render/RenderNodes.h"
#include "nodes/util/UtilNodes.h"
#include "nodes/volume/VolumeNodes.h"

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
    registerLogTextNode(registry);

    // atmosphere/
    registerAtmosphereNode(registry);
    registerNoiseMapNode(registry);
    registerThermalFieldNode(registry);
    registerMapMathNode(registry);
    registerVapourEmitterNode(registry);
    registerThermalIntegratorNode(registry);
    registerCondensationNode(registry);
    registerWriteWeatherReportNode(registry);
    registerVapourPointsNode(registry);

    // fluid/
    registerPrimitiveSimNode(registry);
    registerPrimitiveLoadNode(registry);
    registerWritePrimitiveNodes(registry);
    registerPrimitiveFrameNode(registry);

    // io/
    registerWriteMapNode(registry);
    registerReadMapNode(registry);
    registerWriteParticlesNode(registry);
    registerEncodeVideoNode(registry);
    registerRetimeNode(registry);

    // volume/
    registerVoxelizerNode(registry);
    registerWriteVdbNode(registry);
    registerReadVdbNode(registry);
    registerWritePointsNode(registry);
    registerCombineVolumesNode(registry);
    registerCloudVelocityNode(registry);

    // mapping/
    registerPrimitiveMapperNode(registry);
    registerGenerateCloudNode(registry);
    registerWriteCloudParticlesNode(registry);
    registerPrimitiveSubsetNode(registry);

    // render/
    registerSyntheticCumulusNode(registry);
    registerRendererNode(registry);
    registerWriteImageNode(registry);
    registerWriteCameraNode(registry);
    registerWriteShotNode(registry);
}

}  // namespace cg
