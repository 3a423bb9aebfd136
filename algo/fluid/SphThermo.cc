#include "algo/fluid/SphThermo.h"

#include <algorithm>
#include <cmath>

namespace cg::algo {

namespace {
constexpr double kKelvin = 273.15;
constexpr double kEpsilon = 0.622;    // R_d / R_v
constexpr double kVapourGas = 461.5;  // R_v, J/(kg K)
}  // namespace

double ambientTemperature(const ThermoSettings& s, double z)
{
    return s.groundTemperature - s.ambientLapse * z;
}

double pressureAt(const ThermoSettings& s, double z)
{
    return s.groundPressure * std::exp(-z / s.scaleHeight);
}

double saturationVapourPressure(double celsius)
{
    return 610.78 * std::exp(17.27 * celsius / (celsius + 237.3));
}

double saturationHumidity(double celsius, double pressure)
{
    const double e = saturationVapourPressure(celsius);
    return kEpsilon * e / std::max(pressure - (1.0 - kEpsilon) * e, 1.0);
}

double ambientVapour(const ThermoSettings& s, double z)
{
    return s.ambientHumidity * saturationHumidity(ambientTemperature(s, z), pressureAt(s, z));
}

double buoyancy(const ThermoSettings& s, double z, double temperature, double vapour,
                double condensed)
{
    const double te = ambientTemperature(s, z);
    return s.gravity * ((temperature - te) / (te + kKelvin) +
                        0.608 * (vapour - ambientVapour(s, z)) - condensed);
}

double condense(const ThermoSettings& s, double z, double& temperature, double& vapour,
                double& condensed)
{
    const double p = pressureAt(s, z);
    const double q = s.latentFactor();
    double total = 0.0;
    // Newton steps on q_v - q_s(T + Q dq) = 0; d q_s / dT by Clausius-Clapeyron, so the division
    // by (1 + Q dq_s/dT) accounts for the warming that the condensation itself causes.
    for (int k = 0; k < 3; ++k) {
        const double qs = saturationHumidity(temperature, p);
        const double tk = temperature + kKelvin;
        const double dqs = qs * s.latentHeat / (kVapourGas * tk * tk);
        double dq = (vapour - qs) / (1.0 + q * dqs);
        if (dq < 0.0) dq = std::max(dq, -condensed);  // evaporate at most what is there
        if (dq == 0.0) break;
        vapour -= dq;
        condensed += dq;
        temperature += q * dq;
        total += dq;
    }
    return total;
}

}  // namespace cg::algo
