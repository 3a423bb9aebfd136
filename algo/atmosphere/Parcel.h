#pragma once
/// A parcel lifted through an environment profile: where it condenses (the lifting
/// condensation level), where it becomes warmer than its surroundings (the level of free
/// convection) and where it stops being so (the equilibrium level, near which towers stop and
/// anvils spread), and the energy it gains between them (CAPE). The data of a Skew-T diagram.

#include <vector>

#include "algo/atmosphere/Profile.h"

namespace cg::algo {

/// Height above its start at which a parcel lifted dry from temperature `t` with dew point
/// `td` (C) saturates: its temperature falls at the dry adiabatic 9.76 C/km and its dew point
/// at 1.8 C/km, so they meet (t - td) / 7.96 km higher, about 125 m per C of depression.
double liftingCondensationHeight(double t, double td);

struct ParcelPoint {
    double heightM = 0.0;
    double parcelC = 0.0;       ///< the parcel's temperature
    double environmentC = 0.0;  ///< the environment's at the same height
};

struct ParcelAscent {
    double lclM = 0.0;  ///< lifting condensation level, above sea level
    double lclTemperatureC = 0.0;
    double lfcM = 0.0;        ///< level of free convection; NaN when the parcel never rises freely
    double elM = 0.0;         ///< equilibrium level; NaN without an LFC; the top when never reached
    double capeJPerKg = 0.0;  ///< g int (T_p - T_e) / T_e dz from the LFC to the EL
    double cinJPerKg = 0.0;   ///< the same integral below the LFC where it is negative (<= 0)
    std::vector<ParcelPoint> path;  ///< every `stepM` metres from the start to the profile's top
};

/// Lifts a parcel from `startM` (above sea level) with the environment's temperature and dew
/// point there: dry adiabatically to the LCL, then saturated (moist adiabatic lapse at the
/// environment's pressure, integrated with the midpoint rule every `stepM` metres) to the top
/// of the profile. Buoyancy uses temperatures, not virtual temperatures (ours; the virtual
/// correction is under 1 C). Crossings are interpolated linearly between steps.
ParcelAscent liftParcel(const EnvironmentProfile& environment, double startM, double stepM = 10.0);

/// The same for a parcel that starts at `startM` with its own temperature and dew point
/// (C): a thermal warmer or moister than the air around it.
ParcelAscent liftParcel(const EnvironmentProfile& environment, double startM, double startC,
                        double startDewpointC, double stepM = 10.0);

}  // namespace cg::algo
