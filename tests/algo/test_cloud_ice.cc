// Glaciation: how much of a cloud's condensate is ice, and the crystals' extinction
// (algo/atmosphere/CloudIce.h).

#include <gtest/gtest.h>

#include <stdexcept>

#include "algo/atmosphere/CloudIce.h"
#include "algo/atmosphere/CloudWater.h"

namespace cg::algo {

TEST(CloudIce, NoIceAboveTheFirstIceAllIceBelowHomogeneousFreezingLinearBetween)
{
    const Glaciation g;  // -10 C and -38 C
    EXPECT_EQ(iceFraction(20.0, g), 0.0);
    EXPECT_EQ(iceFraction(-10.0, g), 0.0);
    EXPECT_DOUBLE_EQ(iceFraction(-24.0, g), 0.5);
    EXPECT_DOUBLE_EQ(iceFraction(-17.0, g), 0.25);
    EXPECT_EQ(iceFraction(-38.0, g), 1.0);
    EXPECT_EQ(iceFraction(-60.0, g), 1.0);
}

TEST(CloudIce, ExtinctionIsTheGeometricOpticsOfCrystals)
{
    // 0.1 g/m^3 of crystals of 30 um: 3 x 1e-4 kg/m^3 / (2 x 917 kg/m^3 x 30e-6 m).
    EXPECT_NEAR(extinctionFromIce(0.1, 30e-6), 0.0054526, 1e-6);
    EXPECT_DOUBLE_EQ(extinctionFromIce(0.2, 30e-6), 2.0 * extinctionFromIce(0.1, 30e-6));
    EXPECT_DOUBLE_EQ(extinctionFromIce(0.1, 60e-6), 0.5 * extinctionFromIce(0.1, 30e-6));
    EXPECT_EQ(extinctionFromIce(0.0, 30e-6), 0.0);
}

TEST(CloudIce, AnvilIceHasAMeanFreePathOfHundredsOfMetresWhereDropletsHaveTens)
{
    // A tenth of a gram per m^3, the anvil's typical ice, against the same water as droplets.
    const double ice = 1.0 / extinctionFromIce(0.1, Glaciation{}.effectiveRadius);
    const double droplets = 1.0 / extinctionFromWater(0.1, kContinentalDroplets);
    EXPECT_GT(ice, 100.0);
    EXPECT_LT(ice, 300.0);
    EXPECT_LT(droplets, 40.0);
    EXPECT_GT(ice / droplets, 5.0);
}

TEST(CloudIce, RefusesAnInvertedRangeNoRetentionOrNoCrystals)
{
    EXPECT_NO_THROW(checkGlaciation(Glaciation{}));
    Glaciation g;
    g.endC = g.startC;
    EXPECT_THROW(checkGlaciation(g), std::invalid_argument);
    g = Glaciation{};
    g.retention = 0.0;
    EXPECT_THROW(checkGlaciation(g), std::invalid_argument);
    g = Glaciation{};
    g.effectiveRadius = 0.0;
    EXPECT_THROW(checkGlaciation(g), std::invalid_argument);
}

}  // namespace cg::algo
