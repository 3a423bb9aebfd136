#include "nodes/volume/CloudWaterSetup.h"

#include <cmath>
#include <vector>

#include "nodes/data/AtmosphereData.h"
#include "nodes/data/VapourParticles.h"

namespace cg {

std::unique_ptr<algo::CloudBaseField> cloudBaseOf(const CondensationData& condensation,
                                                  double cellSize)
{
    if (condensation.condensedCount() == 0) return nullptr;
    const VapourParticlesData& p = *condensation.particles;
    return std::make_unique<algo::CloudBaseField>(p.xs().data(), p.ys().data(),
                                                  condensation.condensedHeight.data(),
                                                  condensation.condensedHeight.size(), cellSize);
}

algo::AdiabaticWater adiabaticWaterAt(const Atmosphere& a, double baseZ)
{
    const algo::EnvironmentProfile profile = environmentProfileOf(a);
    const double pressure = profile.pressure(profile.groundHeight() + baseZ);
    // The paper's parcels condense at T_dp; a sounding's at the air's temperature there.
    return algo::AdiabaticWater(a.profile ? a.environmentTemperature(baseZ) : a.dewPoint, pressure);
}

}  // namespace cg
