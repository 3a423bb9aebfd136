// condenseStep (pseudocode lines 9-14): below the dew point a particle condenses, for good;
// the first condensation frame, the height it condensed at and the count follow.

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "algo/atmosphere/Condensation.h"

namespace cg {

TEST(Condensation, ParticlesBelowTheDewPointCondenseAndNeverTurnBack)
{
    const double dewPoint = 5.0;
    const std::vector<float> warm = {10.0f, 6.0f, 20.0f};
    const std::vector<float> z0 = {100.0f, 110.0f, 120.0f}, z1 = {200.0f, 210.0f, 220.0f},
                             z2 = {300.0f, 310.0f, 320.0f};
    const algo::CondensationState f0 =
        algo::condenseStep(nullptr, warm.data(), z0.data(), 3, dewPoint, 0);
    EXPECT_EQ(f0.count, 0u);
    EXPECT_EQ(f0.firstFrame, -1);
    EXPECT_EQ(f0.condensedFrame, (std::vector<std::int32_t>{-1, -1, -1}));

    const std::vector<float> cooler = {4.9f, 5.0f, 20.0f};  // 5.0 is not below the dew point
    const algo::CondensationState f1 =
        algo::condenseStep(&f0, cooler.data(), z1.data(), 3, dewPoint, 1);
    EXPECT_EQ(f1.condensedFrame, (std::vector<std::int32_t>{1, -1, -1}));
    EXPECT_EQ(f1.firstFrame, 1);
    EXPECT_EQ(f1.count, 1u);
    EXPECT_EQ(f1.condensedHeight[0], 200.0f);
    EXPECT_TRUE(std::isnan(f1.condensedHeight[1]));

    const std::vector<float> rewarmed = {30.0f, -1.0f, 20.0f};
    const algo::CondensationState f2 =
        algo::condenseStep(&f1, rewarmed.data(), z2.data(), 3, dewPoint, 2);
    EXPECT_EQ(f2.condensedFrame, (std::vector<std::int32_t>{1, 2, -1}));
    EXPECT_EQ(f2.firstFrame, 1);
    EXPECT_EQ(f2.count, 2u);
    // A particle keeps the height it condensed at; the next one condenses where it is now.
    EXPECT_EQ(f2.condensedHeight[0], 200.0f);
    EXPECT_EQ(f2.condensedHeight[1], 310.0f);
    EXPECT_TRUE(std::isnan(f2.condensedHeight[2]));

    EXPECT_THROW(algo::condenseStep(&f2, rewarmed.data(), z2.data(), 2, dewPoint, 3),
                 std::invalid_argument);
}

}  // namespace cg
