// The cloud's water and its optics (algo/atmosphere/CloudWater.h): the adiabatic liquid water
// against the moist adiabat solved another way, the extinction against its closed form.

#include <gtest/gtest.h>

#include <cmath>

#include "algo/atmosphere/CloudWater.h"
#include "algo/atmosphere/Thermodynamics.h"

namespace cg::algo {

namespace {

namespace th = thermo;

/// The adiabatic water h metres above a base at t0 (C), p0 (hPa), solved independently of
/// the lapse-rate integration: a saturated parcel keeps its moist static energy
/// c_pd T + g z + L r_s(T, p) (the same approximations as the AMS lapse rate), so at each
/// height T is the root of that balance (bisection), with p hydrostatic in 1 m layers.
double referenceWater(double t0, double p0, double h)
{
    const double r0 = th::saturationMixingRatio(t0, p0);
    const double energy = th::kDryHeatCapacity * t0 + th::kLatentHeat * r0;
    double t = t0, p = p0;
    for (double z = 1.0; z <= h + 1e-9; z += 1.0) {
        double lo = t - 1.0, hi = t;
        const double pGuess = th::hydrostaticPressure(p, t, t - 0.006, 1.0);
        for (int i = 0; i < 60; ++i) {
            const double mid = 0.5 * (lo + hi);
            const double e = th::kDryHeatCapacity * mid + th::kGravity * z +
                             th::kLatentHeat * th::saturationMixingRatio(mid, pGuess);
            (e > energy ? hi : lo) = mid;
        }
        const double tNext = 0.5 * (lo + hi);
        p = th::hydrostaticPressure(p, t, tNext, 1.0);
        t = tNext;
    }
    const double rhoDry =
        (p - th::saturationVapourPressure(t)) * 100.0 / (th::kDryGasConstant * (t + th::kKelvin));
    return 1000.0 * rhoDry * (r0 - th::saturationMixingRatio(t, p));
}

}  // namespace

TEST(CloudWater, AdiabaticWaterFollowsTheMoistAdiabatSolvedByItsStaticEnergy)
{
    const AdiabaticWater water(16.0, 860.0);
    EXPECT_EQ(water.at(0.0), 0.0);
    EXPECT_EQ(water.at(-50.0), 0.0);
    for (const double h : {100.0, 500.0, 1000.0, 2000.0, 4000.0}) {
        const double ref = referenceWater(16.0, 860.0, h);
        EXPECT_NEAR(water.at(h), ref, 0.03 * ref) << h << " m above the base";
    }
}

TEST(CloudWater, NearAWarmBaseTheWaterGrowsAboutTwoGramsPerCubicMetrePerKilometre)
{
    const AdiabaticWater water(16.0, 860.0);
    const double perKm = water.at(200.0) / 0.2;
    EXPECT_GT(perKm, 1.6);
    EXPECT_LT(perKm, 2.6);
    // Colder bases hold less: the rate falls with temperature.
    EXPECT_LT(AdiabaticWater(-10.0, 500.0).at(200.0), 0.5 * water.at(200.0));
    // The parcel cools at the moist rate near the base (4-6 C per km when warm).
    EXPECT_NEAR((16.0 - water.temperature(1000.0)), 5.0, 1.0);
}

TEST(CloudWater, ExtinctionIsItsClosedFormFromWaterAndDropletNumber)
{
    constexpr double kPi = 3.14159265358979323846;
    for (const DropletPopulation d : {kContinentalDroplets, kMaritimeDroplets})
        for (const double lwc : {0.05, 0.5, 1.0, 2.5}) {
            const double r = std::cbrt(3.0 * lwc * 1e-3 /
                                       (4.0 * kPi * 1000.0 * d.k * d.concentrationPerCm3 * 1e6));
            EXPECT_NEAR(effectiveRadius(lwc, d), r, 1e-12);
            EXPECT_NEAR(extinctionFromWater(lwc, d), 1.5 * lwc * 1e-3 / (1000.0 * r),
                        1e-9 * extinctionFromWater(lwc, d));
        }
    // sigma ~ LWC^(2/3) N^(1/3): 8 times the water gives 4 times the extinction, 8 times the
    // droplets twice.
    const DropletPopulation few{100.0, 0.8}, many{800.0, 0.8};
    EXPECT_NEAR(extinctionFromWater(8.0, few), 4.0 * extinctionFromWater(1.0, few), 1e-12);
    EXPECT_NEAR(extinctionFromWater(1.0, many), 2.0 * extinctionFromWater(1.0, few), 1e-12);
    EXPECT_EQ(extinctionFromWater(0.0, few), 0.0);
}

TEST(CloudWater, CumulusWaterGivesMeanFreePathsOfTensOfMetresAndDropletsOfMicrons)
{
    // 0.3 to 2 g/m^3, continental and maritime: mean free paths 3 to 30 m, radii 5 to 20 um.
    for (const DropletPopulation d : {kContinentalDroplets, kMaritimeDroplets})
        for (const double lwc : {0.3, 1.0, 2.0}) {
            const double path = 1.0 / extinctionFromWater(lwc, d);
            EXPECT_GT(path, 3.0);
            EXPECT_LT(path, 30.0);
            const double r = effectiveRadius(lwc, d);
            EXPECT_GT(r, 5e-6);
            EXPECT_LT(r, 20e-6);
        }
    // Maritime clouds have fewer, larger droplets: less extinction for the same water.
    EXPECT_LT(extinctionFromWater(1.0, kMaritimeDroplets),
              extinctionFromWater(1.0, kContinentalDroplets));
}

TEST(CloudWater, DropletAsymmetryIsMieTheorysRangeForCloudDroplets)
{
    EXPECT_NEAR(dropletAsymmetry(5e-6), 0.85, 0.005);
    EXPECT_NEAR(dropletAsymmetry(15e-6), 0.868, 0.005);
    EXPECT_LT(dropletAsymmetry(5e-6), dropletAsymmetry(10e-6));
}

TEST(CloudWater, RefusesABaseOutsideTheAtmosphere)
{
    EXPECT_THROW(AdiabaticWater(15.0, 50.0), std::invalid_argument);
    EXPECT_THROW(AdiabaticWater(std::nan(""), 850.0), std::invalid_argument);
}

}  // namespace cg::algo
