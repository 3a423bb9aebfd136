#include "algo/atmosphere/Parcel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "algo/atmosphere/Thermodynamics.h"

namespace cg::algo {

namespace {

constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

/// The parcel's temperature at z1 when it has `t` at z, below or above the LCL.
double parcelStep(const EnvironmentProfile& env, double lcl, double z, double t, double z1)
{
    if (z1 <= lcl) return t - thermo::kDryAdiabaticLapse * (z1 - z);
    if (z < lcl) {  // the step crosses the LCL: dry to it, saturated from it
        t -= thermo::kDryAdiabaticLapse * (lcl - z);
        z = lcl;
    }
    const double dz = z1 - z;
    const double half = t - 0.5 * dz * thermo::moistAdiabaticLapse(t, env.pressure(z));
    return t - dz * thermo::moistAdiabaticLapse(half, env.pressure(z + 0.5 * dz));
}

/// Buoyancy per unit mass, g (T_p - T_e) / T_e, m/s^2.
double buoyancy(const ParcelPoint& p)
{
    return thermo::kGravity * (p.parcelC - p.environmentC) / (p.environmentC + thermo::kKelvin);
}

/// The first height in [from, top] where the parcel's excess temperature goes from <= 0 to
/// > 0 (rising = true) or from > 0 to <= 0 (rising = false), interpolated; NaN if none.
double crossing(const std::vector<ParcelPoint>& path, double from, bool rising)
{
    for (std::size_t i = 1; i < path.size(); ++i) {
        const ParcelPoint& a = path[i - 1];
        const ParcelPoint& b = path[i];
        if (b.heightM < from) continue;
        const double da = a.parcelC - a.environmentC;
        const double db = b.parcelC - b.environmentC;
        if (rising ? db <= 0.0 : (db > 0.0 || da <= 0.0)) continue;
        if (rising && da > 0.0) return std::max(a.heightM, from);  // buoyant already at a
        const double z = a.heightM + (b.heightM - a.heightM) * da / (da - db);  // da != db
        return std::max(z, from);
    }
    return kNone;
}

/// int g (T_p - T_e) / T_e dz over [lo, hi] (trapezoids, clipped to the range); with
/// `negativeOnly` only where the buoyancy is negative.
double integrate(const std::vector<ParcelPoint>& path, double lo, double hi, bool negativeOnly)
{
    double sum = 0.0;
    for (std::size_t i = 1; i < path.size(); ++i) {
        const ParcelPoint& a = path[i - 1];
        const ParcelPoint& b = path[i];
        const double z0 = std::max(a.heightM, lo), z1 = std::min(b.heightM, hi);
        if (!(z1 > z0)) continue;
        const auto at = [&](double z) {
            const double w = (z - a.heightM) / (b.heightM - a.heightM);
            const double v = (1.0 - w) * buoyancy(a) + w * buoyancy(b);
            return negativeOnly ? std::min(v, 0.0) : v;
        };
        sum += 0.5 * (at(z0) + at(z1)) * (z1 - z0);
    }
    return sum;
}

}  // namespace

double liftingCondensationHeight(double t, double td)
{
    return std::max(0.0, t - td) / (thermo::kDryAdiabaticLapse - thermo::kParcelDewpointLapse);
}

ParcelAscent liftParcel(const EnvironmentProfile& env, double startM, double stepM)
{
    return liftParcel(env, startM, env.temperature(startM), env.dewpoint(startM), stepM);
}

ParcelAscent liftParcel(const EnvironmentProfile& env, double startM, double t0,
                        double startDewpointC, double stepM)
{
    if (!(stepM > 0.0) || !(startM < env.topHeight()))
        throw std::invalid_argument(
            "liftParcel: the step must be positive and the start below "
            "the profile's top");
    ParcelAscent a;
    a.lclM = startM + liftingCondensationHeight(t0, startDewpointC);
    a.lclTemperatureC = t0 - thermo::kDryAdiabaticLapse * (a.lclM - startM);

    double z = startM;
    double t = t0;
    a.path.push_back({z, t, env.temperature(z)});
    while (z < env.topHeight()) {
        const double z1 = std::min(z + stepM, env.topHeight());
        t = parcelStep(env, a.lclM, z, t, z1);
        z = z1;
        a.path.push_back({z, t, env.temperature(z)});
    }

    a.lfcM = crossing(a.path, a.lclM, /*rising=*/true);
    if (std::isnan(a.lfcM)) {
        a.elM = kNone;
        return a;
    }
    a.elM = crossing(a.path, a.lfcM, /*rising=*/false);
    if (std::isnan(a.elM)) a.elM = env.topHeight();  // buoyant to the top of the profile
    a.capeJPerKg = integrate(a.path, a.lfcM, a.elM, false);
    a.cinJPerKg = integrate(a.path, startM, a.lfcM, true);
    return a;
}

}  // namespace cg::algo
