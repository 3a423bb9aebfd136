// The convective condensation level and temperature (algo/atmosphere/Convective.h) against a
// solution computed here with another saturation formula and the closed-form hydrostatic
// pressure of a constant lapse rate.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "algo/atmosphere/Convective.h"
#include "algo/atmosphere/Thermodynamics.h"

namespace cg::algo {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// T(z) = 30 C - 8 C/km z from sea level to 12 km, every 100 m; 18 C dew point at the ground.
EnvironmentProfile linearProfile(double surfaceDewpoint)
{
    std::vector<ProfileLevel> levels;
    for (double z = 0.0; z <= 12000.0; z += 100.0)
        levels.push_back({z, 30.0 - 8e-3 * z, z == 0.0 ? surfaceDewpoint : kNaN, kNaN, kNaN, kNaN});
    return EnvironmentProfile(levels);
}

/// Magnus's saturation pressure (Alduchov and Eskridge 1996), not Bolton's, and the exact
/// pressure of a constant lapse rate from 1013.25 hPa.
double magnus(double t) { return 6.1094 * std::exp(17.625 * t / (t + 243.04)); }
double pressureAt(double z)
{
    const double t0 = 303.15, lapse = 8e-3, g = 9.80665, r = 287.053;
    return 1013.25 * std::pow((t0 - lapse * z) / t0, g / (r * lapse));
}

}  // namespace

TEST(Convective, TheCclAndConvectiveTemperatureOfALinearProfileAgreeWithAnIndependentSolution)
{
    const EnvironmentProfile profile = linearProfile(18.0);
    const ConvectiveLevels c = convectiveLevels(profile);
    // Independently: the surface mixing ratio, then bisection for the height where the
    // temperature meets that mixing ratio's dew point (vapour pressure w p / (0.622 + w)).
    const double e0 = magnus(18.0), w = 0.622 * e0 / (1013.25 - e0);
    const auto gap = [&](double z) {
        const double e = w * pressureAt(z) / (0.622 + w);
        const double l = std::log(e / 6.1094);
        return (30.0 - 8e-3 * z) - 243.04 * l / (17.625 - l);
    };
    double lo = 0.0, hi = 5000.0;
    for (int i = 0; i < 60; ++i) (gap(0.5 * (lo + hi)) > 0.0 ? lo : hi) = 0.5 * (lo + hi);
    const double ccl = 0.5 * (lo + hi);
    EXPECT_NEAR(c.cclM, ccl, 15.0);
    EXPECT_NEAR(c.cclM, 1935.0, 60.0);  // (30 - 18) / (8 - 1.8) km, the rule of thumb
    // Potential temperature is kept on the way down: T_c = T_ccl (p_s / p_ccl)^0.2857.
    const double tc =
        (30.0 - 8e-3 * ccl + 273.15) * std::pow(1013.25 / pressureAt(ccl), 0.2857) - 273.15;
    EXPECT_NEAR(c.convectiveTemperatureC, tc, 0.15);
    EXPECT_GT(c.convectiveTemperatureC, 30.0);  // the ground must warm to make cumulus
}

TEST(Convective, TheMixingRatioDewpointInvertsTheSaturationMixingRatio)
{
    for (double t : {-30.0, -5.0, 0.0, 12.5, 25.0, 35.0})
        for (double p : {300.0, 700.0, 1000.0})
            EXPECT_NEAR(mixingRatioDewpoint(thermo::saturationMixingRatio(t, p), p), t, 1e-9);
}

TEST(Convective, AirTooDryForCumulusHasNoCcl)
{
    // A dew point of -60 C: the mixing-ratio line stays below the temperature to 12 km.
    EXPECT_THROW(convectiveLevels(linearProfile(-60.0)), std::invalid_argument);
    EXPECT_THROW(convectiveLevels(linearProfile(18.0), 0.0), std::invalid_argument);
}

}  // namespace cg::algo
