#include "algo/atmosphere/CloudWater.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "algo/atmosphere/Thermodynamics.h"

namespace cg::algo {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Dry air density, kg/m^3, of saturated air at temperature tC and pressure pHPa.
double dryAirDensity(double tC, double pHPa)
{
    const double dryPressurePa = (pHPa - thermo::saturationVapourPressure(tC)) * 100.0;
    return dryPressurePa / (thermo::kDryGasConstant * (tC + thermo::kKelvin));
}

}  // namespace

AdiabaticWater::AdiabaticWater(double baseTemperatureC, double basePressureHPa, double depth,
                               double step)
    : mStep(step)
{
    if (!(step > 0.0) || !(depth >= step) || !std::isfinite(baseTemperatureC) ||
        !(basePressureHPa > 100.0 && basePressureHPa < 1200.0))
        throw std::invalid_argument(
            "adiabatic water: base temperature, pressure or depth out of range");
    const double r0 = thermo::saturationMixingRatio(baseTemperatureC, basePressureHPa);
    double t = baseTemperatureC, p = basePressureHPa;
    const auto n = static_cast<std::size_t>(depth / step) + 1;
    mWater.reserve(n);
    mTemperature.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double condensed = std::max(0.0, r0 - thermo::saturationMixingRatio(t, p));
        mWater.push_back(1000.0 * dryAirDensity(t, p) * condensed);
        mTemperature.push_back(t);
        // Midpoint step along the saturated adiabat; the pressure hydrostatic over the layer.
        const double tMid = t - 0.5 * step * thermo::moistAdiabaticLapse(t, p);
        const double pMid = thermo::hydrostaticPressure(p, t, tMid, 0.5 * step);
        const double tNext = t - step * thermo::moistAdiabaticLapse(tMid, pMid);
        p = thermo::hydrostaticPressure(p, t, tNext, step);
        t = tNext;
    }
}

double AdiabaticWater::lookup(const std::vector<double>& table, double h, double step)
{
    if (!(h > 0.0)) return table.front();
    const double at = h / step;
    const auto i = static_cast<std::size_t>(at);
    if (i + 1 >= table.size()) return table.back();
    const double w = at - static_cast<double>(i);
    return table[i] + w * (table[i + 1] - table[i]);
}

double AdiabaticWater::at(double h) const { return h > 0.0 ? lookup(mWater, h, mStep) : 0.0; }

double AdiabaticWater::temperature(double h) const { return lookup(mTemperature, h, mStep); }

double effectiveRadius(double lwcGramsPerM3, const DropletPopulation& d)
{
    if (!(lwcGramsPerM3 > 0.0)) return 0.0;
    const double lwc = lwcGramsPerM3 * 1e-3;       // kg/m^3
    const double n = d.concentrationPerCm3 * 1e6;  // 1/m^3
    return std::cbrt(3.0 * lwc / (4.0 * kPi * kWaterDensity * d.k * n));
}

double extinctionFromWater(double lwcGramsPerM3, const DropletPopulation& d)
{
    if (!(lwcGramsPerM3 > 0.0)) return 0.0;
    return 3.0 * lwcGramsPerM3 * 1e-3 / (2.0 * kWaterDensity * effectiveRadius(lwcGramsPerM3, d));
}

double dropletAsymmetry(double effectiveRadiusM)
{
    return 0.87 - 0.07 * std::exp(-effectiveRadiusM / 4e-6);
}

}  // namespace cg::algo
