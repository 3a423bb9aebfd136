#include "algo/atmosphere/Convective.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "algo/atmosphere/Thermodynamics.h"

namespace cg::algo {

double mixingRatioDewpoint(double w, double pressureHPa)
{
    const double e = w * pressureHPa / (thermo::kMolarMassRatio + w);
    const double l = std::log(e / 6.112);
    return 243.5 * l / (17.67 - l);
}

ConvectiveLevels convectiveLevels(const EnvironmentProfile& profile, double stepM)
{
    if (!(stepM > 0.0)) throw std::invalid_argument("convectiveLevels: the step must be > 0");
    ConvectiveLevels c;
    const double ground = profile.groundHeight();
    const double surfacePressure = profile.pressure(ground);
    c.surfaceMixingRatio = thermo::saturationMixingRatio(profile.dewpoint(ground), surfacePressure);
    // How much warmer the environment is than the line's dew point: the CCL is its first zero.
    const auto excess = [&](double z) {
        return profile.temperature(z) -
               mixingRatioDewpoint(c.surfaceMixingRatio, profile.pressure(z));
    };
    double z0 = ground, e0 = excess(z0);
    if (e0 <= 0.0) {
        c.cclM = ground;  // saturated at the ground: fog, not cumulus
    } else {
        for (;;) {
            if (z0 >= profile.topHeight())
                throw std::invalid_argument(
                    "the sounding's surface mixing-ratio line never meets its temperature: no "
                    "convective condensation level below the top");
            const double z1 = std::min(z0 + stepM, profile.topHeight()), e1 = excess(z1);
            if (e1 <= 0.0) {
                c.cclM = z0 + (z1 - z0) * e0 / (e0 - e1);
                break;
            }
            z0 = z1;
            e0 = e1;
        }
    }
    c.cclTemperatureC = profile.temperature(c.cclM);
    const double kappa = thermo::kDryGasConstant / thermo::kDryHeatCapacity;
    c.convectiveTemperatureC = (c.cclTemperatureC + thermo::kKelvin) *
                                   std::pow(surfacePressure / profile.pressure(c.cclM), kappa) -
                               thermo::kKelvin;
    return c;
}

}  // namespace cg::algo
