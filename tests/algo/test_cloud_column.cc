// Cloud base, top and fraction by height from condensation particles.

#include <gtest/gtest.h>

#include <cmath>

#include "algo/atmosphere/CloudColumn.h"

namespace cg::algo {

TEST(CloudColumn, BaseTopAndFractionOfAKnownBlock)
{
    // A 10 x 10 km domain (marked by two vapour particles at its corners) and a condensed
    // block over its western half, 1000 to 2000 m high, one particle per 100 m cell and level.
    std::vector<float> x{0.0f, 9999.0f}, y{0.0f, 9999.0f}, z{0.0f, 0.0f};
    std::vector<std::int32_t> frame{-1, -1};
    for (int ix = 0; ix < 50; ++ix)
        for (int iy = 0; iy < 100; ++iy)
            for (float h : {1000.0f, 1300.0f, 1600.0f, 1999.0f}) {
                x.push_back(ix * 100.0f + 50.0f);
                y.push_back(iy * 100.0f + 50.0f);
                z.push_back(h);
                frame.push_back(7);
            }
    const CloudColumn c =
        cloudColumn(x.data(), y.data(), z.data(), frame.data(), x.size(), 250.0, 100.0);
    EXPECT_EQ(c.condensed, 50u * 100u * 4u);
    EXPECT_EQ(c.baseM, 1000.0);
    EXPECT_EQ(c.topM, 1999.0);
    ASSERT_EQ(c.fraction.size(), 8u);  // bins up to the top: [1750, 2000) is the last
    for (std::size_t k = 0; k < c.fraction.size(); ++k) {
        const bool holds = k == 4 || k == 5 || k == 6 || k == 7;  // 1000, 1300, 1600, 1999
        EXPECT_DOUBLE_EQ(c.fraction[k], holds ? 0.5 : 0.0) << "bin " << k;
    }
}

TEST(CloudColumn, NoCondensationHasNoBaseOrTop)
{
    const float x[] = {0.0f, 10.0f}, y[] = {0.0f, 10.0f}, z[] = {100.0f, 200.0f};
    const std::int32_t frame[] = {-1, -1};
    const CloudColumn c = cloudColumn(x, y, z, frame, 2, 250.0, 100.0);
    EXPECT_EQ(c.condensed, 0u);
    EXPECT_TRUE(std::isnan(c.baseM));
    EXPECT_TRUE(std::isnan(c.topM));
    EXPECT_TRUE(c.fraction.empty());
}

}  // namespace cg::algo
