#include "nodes/data/DataTypes.h"

#include "nodes/data/AtmosphereData.h"
#include "nodes/data/CameraPath.h"
#include "nodes/data/CloudParticles.h"
#include "nodes/data/CloudSources.h"
#include "nodes/data/FogVolume.h"
#include "nodes/data/Image.h"
#include "nodes/data/Map2D.h"
#include "nodes/data/PrimitiveSet.h"
#include "nodes/data/VapourParticles.h"
#include "nodes/data/VelocityVolume.h"

namespace cg {

void registerNodeDataTypes(Registry& registry)
{
    registerAtmosphereType(registry);
    registerCameraPathType(registry);
    registerCloudParticlesType(registry);
    registerCloudSourcesType(registry);
    registerFogVolumeType(registry);
    registerImageType(registry);
    registerMap2DType(registry);
    registerPrimitiveSetType(registry);
    registerVapourParticleTypes(registry);
    registerVelocityVolumeType(registry);
}

}  // namespace cg
