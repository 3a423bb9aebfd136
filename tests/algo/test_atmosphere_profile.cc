// Real atmospheres (algo/atmosphere/Thermodynamics, Profile, Parcel): textbook values, the
// ICAO standard atmosphere's closed form, interpolation, and a lifted parcel's levels.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "algo/atmosphere/Parcel.h"
#include "algo/atmosphere/Profile.h"
#include "algo/atmosphere/Thermodynamics.h"

namespace cg::algo {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

ProfileLevel level(double z, double t, double td = kNaN, double p = kNaN, double east = kNaN,
                   double north = kNaN)
{
    return {z, t, td, p, east, north};
}

}  // namespace

TEST(Thermodynamics, SaturationVapourPressureMatchesTables)
{
    // WMO / Smithsonian tables over water: 6.112 hPa at 0 C, 12.28 at 10 C, 23.39 at 20 C,
    // 42.46 at 30 C, 2.86 at -10 C.
    EXPECT_NEAR(thermo::saturationVapourPressure(0.0), 6.112, 0.001);
    EXPECT_NEAR(thermo::saturationVapourPressure(10.0) / 12.28, 1.0, 0.003);
    EXPECT_NEAR(thermo::saturationVapourPressure(20.0) / 23.39, 1.0, 0.003);
    EXPECT_NEAR(thermo::saturationVapourPressure(30.0) / 42.46, 1.0, 0.003);
    EXPECT_NEAR(thermo::saturationVapourPressure(-10.0) / 2.863, 1.0, 0.005);
}

TEST(Thermodynamics, MoistAdiabaticLapseMatchesTheTextbookAndTendsToTheDryRate)
{
    // Saturated-adiabatic lapse rates at 1000 hPa (AMS Glossary): about 6.4 C/km at 0 C and
    // 4.3 C/km at 20 C; in the cold upper air it approaches the dry 9.76 C/km.
    EXPECT_NEAR(thermo::moistAdiabaticLapse(0.0, 1000.0) * 1e3, 6.4, 0.15);
    EXPECT_NEAR(thermo::moistAdiabaticLapse(20.0, 1000.0) * 1e3, 4.3, 0.15);
    EXPECT_NEAR(thermo::moistAdiabaticLapse(-60.0, 200.0) * 1e3, 9.76, 0.15);
    EXPECT_LT(thermo::moistAdiabaticLapse(25.0, 1000.0), thermo::moistAdiabaticLapse(5.0, 1000.0));
    EXPECT_NEAR(thermo::kDryAdiabaticLapse * 1e3, 9.76, 0.01);
}

TEST(Profile, StandardAtmosphereMatchesTheIcaoClosedForm)
{
    const EnvironmentProfile p = standardAtmosphere(15.0, 5.0, 11000.0);
    EXPECT_DOUBLE_EQ(p.temperature(0.0), 15.0);
    EXPECT_NEAR(p.temperature(5000.0), 15.0 - 32.5, 1e-9);
    EXPECT_NEAR(p.temperature(11000.0), -56.5, 1e-9);
    EXPECT_NEAR(p.temperature(15000.0), -56.5, 1e-9);  // isothermal above the tropopause
    // ICAO: p = p0 (T / T0)^(g / (R L)) in the troposphere, exponential above.
    const double exponent = thermo::kGravity / (thermo::kDryGasConstant * 6.5e-3);
    const auto icao = [&](double z) {
        const double t0 = 288.15;
        if (z <= 11000.0) return 1013.25 * std::pow((t0 - 6.5e-3 * z) / t0, exponent);
        const double p11 = 1013.25 * std::pow((t0 - 6.5e-3 * 11000.0) / t0, exponent);
        return p11 *
               std::exp(-thermo::kGravity * (z - 11000.0) / (thermo::kDryGasConstant * 216.65));
    };
    for (double z : {1000.0, 5000.0, 11000.0, 16000.0, 20000.0})
        EXPECT_NEAR(p.pressure(z) / icao(z), 1.0, 1e-5) << z;
    EXPECT_NEAR(icao(11000.0), 226.32, 0.05);                             // the published value
    EXPECT_NEAR(p.temperature(3000.0) - p.dewpoint(3000.0), 10.0, 1e-9);  // depression kept
}

TEST(Profile, InterpolatesInHeightAndFillsWhatTheSoundingLacks)
{
    const EnvironmentProfile p(
        {level(100.0, 20.0, 10.0, 1000.0, 0.0, 0.0), level(1100.0, 14.0, kNaN, kNaN, kNaN, kNaN),
         level(2100.0, 8.0, 2.0, 800.0, 10.0, -4.0), level(3100.0, 2.0, kNaN, kNaN, kNaN, kNaN)});
    EXPECT_DOUBLE_EQ(p.temperature(600.0), 17.0);
    EXPECT_DOUBLE_EQ(p.temperature(0.0), 20.0);    // held below the ground level
    EXPECT_DOUBLE_EQ(p.temperature(9000.0), 2.0);  // and above the top
    EXPECT_DOUBLE_EQ(p.dewpoint(1100.0), 6.0);     // interpolated between 10 and 2
    EXPECT_DOUBLE_EQ(p.dewpoint(3100.0), -4.0);    // the last depression (6 C) kept
    // A missing pressure is hydrostatic from the level below.
    EXPECT_NEAR(p.pressure(1100.0), thermo::hydrostaticPressure(1000.0, 20.0, 14.0, 1000.0), 1e-9);
    EXPECT_NEAR(p.pressure(1600.0), std::sqrt(p.pressure(1100.0) * 800.0), 1e-9);  // log-linear
    const Wind w = p.wind(1100.0);  // halfway between calm and (10, -4)
    EXPECT_DOUBLE_EQ(w.east, 5.0);
    EXPECT_DOUBLE_EQ(w.north, -2.0);
    EXPECT_DOUBLE_EQ(p.wind(3100.0).east, 10.0);  // the last wind kept above

    const EnvironmentProfile calm({level(0.0, 20.0, 10.0), level(1000.0, 14.0)});
    EXPECT_EQ(calm.wind(500.0).east, 0.0);
    EXPECT_NEAR(calm.pressure(0.0), 1013.25, 1e-9);  // from sea level when no level has one

    EXPECT_THROW(EnvironmentProfile({level(0.0, 20.0, 10.0)}), std::invalid_argument);
    EXPECT_THROW(EnvironmentProfile({level(0.0, 20.0), level(1000.0, 14.0)}),
                 std::invalid_argument);  // no ground dew point
    EXPECT_THROW(EnvironmentProfile({level(0.0, 20.0, 10.0), level(0.0, 14.0)}),
                 std::invalid_argument);  // heights must increase
}

TEST(Parcel, CondensesAt125MetresPerDegreeOfDewPointDepression)
{
    EXPECT_NEAR(liftingCondensationHeight(24.0, 16.0), 8.0 * 125.0, 0.02 * 8.0 * 125.0);
    EXPECT_EQ(liftingCondensationHeight(10.0, 10.0), 0.0);
    const EnvironmentProfile env = standardAtmosphere(24.0, 16.0, 11000.0);
    const ParcelAscent a = liftParcel(env, 0.0);
    EXPECT_NEAR(a.lclM, 8.0 / (9.76e-3 - 1.8e-3), 2.0);
    EXPECT_NEAR(a.lclTemperatureC, 24.0 - 9.76e-3 * a.lclM, 0.01);
    // Dry below the LCL: 9.76 C/km exactly.
    EXPECT_NEAR(a.path[50].parcelC, 24.0 - 9.76e-3 * 500.0, 0.01);
}

TEST(Parcel, ATroposphericParcelRisesFreelyToNearTheTropopause)
{
    // A warm, moist ground under a standard troposphere: conditionally unstable, so the parcel
    // is free above its LCL and stops being buoyant in the isothermal stratosphere.
    const EnvironmentProfile env = standardAtmosphere(30.0, 24.0, 12000.0);
    const ParcelAscent a = liftParcel(env, 0.0);
    ASSERT_FALSE(std::isnan(a.lfcM));
    EXPECT_GE(a.lfcM, a.lclM);
    EXPECT_LT(a.lfcM, a.lclM + 1000.0);
    EXPECT_GT(a.elM, 10000.0);
    EXPECT_LT(a.elM, 16000.0);
    EXPECT_GT(a.capeJPerKg, 1000.0);  // a deep-convection day
    EXPECT_LE(a.cinJPerKg, 0.0);
    // The EL is a crossing: warmer just below, colder just above.
    const auto excess = [&](double z) {
        for (std::size_t i = 1; i < a.path.size(); ++i)
            if (a.path[i].heightM >= z) return a.path[i].parcelC - a.path[i].environmentC;
        return 0.0;
    };
    EXPECT_GT(excess(a.elM - 50.0), 0.0);
    EXPECT_LT(excess(a.elM + 50.0), 0.0);
    // CAPE is the integral of the path's buoyancy from LFC to EL (midpoint sums, 10 m steps).
    double cape = 0.0;
    for (std::size_t i = 1; i < a.path.size(); ++i) {
        const double z = 0.5 * (a.path[i - 1].heightM + a.path[i].heightM);
        if (z < a.lfcM || z > a.elM) continue;
        const double tp = 0.5 * (a.path[i - 1].parcelC + a.path[i].parcelC);
        const double te = 0.5 * (a.path[i - 1].environmentC + a.path[i].environmentC);
        cape += thermo::kGravity * (tp - te) / (te + thermo::kKelvin) * 10.0;
    }
    EXPECT_NEAR(a.capeJPerKg / cape, 1.0, 0.01);
}

TEST(Parcel, AStableProfileHasNoFreeConvection)
{
    // An isothermal atmosphere: a lifted parcel is always colder than its surroundings.
    const EnvironmentProfile env({level(0.0, 15.0, 5.0), level(10000.0, 15.0)});
    const ParcelAscent a = liftParcel(env, 0.0);
    EXPECT_TRUE(std::isnan(a.lfcM));
    EXPECT_TRUE(std::isnan(a.elM));
    EXPECT_EQ(a.capeJPerKg, 0.0);
}

}  // namespace cg::algo
