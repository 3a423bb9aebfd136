#include "nodes/data/DataTypes.h"

#include "nodes/data/AtmosphereData.h"
#include "nodes/data/Map2D.h"
#include "nodes/data/VapourParticles.h"

namespace cg {

void registerNodeDataTypes(Registry& registry)
{
    registerAtmosphereType(registry);
    registerMap2DType(registry);
    registerVapourParticleTypes(registry);
}

}  // namespace cg
