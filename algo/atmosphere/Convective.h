#pragma once
/// The convective condensation level and the convective temperature of a sounding: the
/// forecaster's way to tell where afternoon cumulus will form. Surface air keeps its mixing
/// ratio as it rises, so its dew point follows the mixing-ratio line through the surface dew
/// point; where that line meets the environment's temperature is the CCL. A surface parcel
/// heated to the convective temperature T_c (the CCL's temperature brought down the dry
/// adiabat to the surface pressure, T_c = T_ccl (p_s / p_ccl)^(R_d / c_pd)) rises dry and
/// saturates exactly there. (AMS Glossary, "convective condensation level", "convective
/// temperature".) Heights above sea level in metres, temperatures in C, pressures in hPa.

#include "algo/atmosphere/Profile.h"

namespace cg::algo {

struct ConvectiveLevels {
    double cclM = 0.0;                    ///< convective condensation level, above sea level
    double cclTemperatureC = 0.0;         ///< the environment's temperature there
    double convectiveTemperatureC = 0.0;  ///< T_c at the ground
    double surfaceMixingRatio = 0.0;      ///< kg/kg, from the ground's dew point and pressure
};

/// The dew point (C) of air with mixing ratio w (kg/kg) at pressure p (hPa): Bolton's
/// saturation formula inverted at the vapour pressure e = w p / (epsilon + w).
double mixingRatioDewpoint(double w, double pressureHPa);

/// The CCL, found by stepping up from the ground every `stepM` metres to the first height
/// where the environment is no warmer than the surface mixing-ratio line's dew point
/// (interpolated linearly between steps), and T_c from it. Throws std::invalid_argument when
/// the line never meets the temperature below the profile's top (air too dry to form
/// cumulus by heating alone) or stepM <= 0.
ConvectiveLevels convectiveLevels(const EnvironmentProfile& profile, double stepM = 10.0);

}  // namespace cg::algo
