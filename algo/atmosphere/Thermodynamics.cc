#include "algo/atmosphere/Thermodynamics.h"

#include <cmath>

namespace cg::algo::thermo {

double saturationVapourPressure(double temperatureC)
{
    return 6.112 * std::exp(17.67 * temperatureC / (temperatureC + 243.5));
}

double saturationMixingRatio(double temperatureC, double pressureHPa)
{
    const double e = saturationVapourPressure(temperatureC);
    return kMolarMassRatio * e / (pressureHPa - e);
}

double moistAdiabaticLapse(double temperatureC, double pressureHPa)
{
    const double t = temperatureC + kKelvin;
    const double r = saturationMixingRatio(temperatureC, pressureHPa);
    const double numerator = kGravity * (1.0 + kLatentHeat * r / (kDryGasConstant * t));
    const double denominator = kDryHeatCapacity + kLatentHeat * kLatentHeat * r * kMolarMassRatio /
                                                      (kDryGasConstant * t * t);
    return numerator / denominator;
}

double hydrostaticPressure(double p0HPa, double t0C, double t1C, double dz)
{
    const double meanKelvin = 0.5 * (t0C + t1C) + kKelvin;
    return p0HPa * std::exp(-kGravity * dz / (kDryGasConstant * meanKelvin));
}

}  // namespace cg::algo::thermo
