#include "nodes/volume/CloudWaterSetup.h"

#include <cmath>
#include <vector>

#include "algo/atmosphere/Thermodynamics.h"
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
    if (a.profile) {
        const double z = a.profile->groundHeight() + baseZ;
        return algo::AdiabaticWater(a.environmentTemperature(baseZ), a.profile->pressure(z));
    }
    // Eq. 9's column, hydrostatic in 10 m layers from the standard sea-level pressure.
    constexpr double kLayer = 10.0;
    double p = 1013.25;
    for (double z = 0.0; z < baseZ; z += kLayer) {
        const double dz = std::min(kLayer, baseZ - z);
        p = algo::thermo::hydrostaticPressure(p, a.environmentTemperature(z),
                                              a.environmentTemperature(z + dz), dz);
    }
    return algo::AdiabaticWater(a.dewPoint, p);
}

}  // namespace cg
