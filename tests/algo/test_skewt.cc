// The skew-T diagram: each curve where the axes put it, the isotherms at 45 degrees, the
// parcel's levels as ticks and a cloud's extent as a bar.

#include <gtest/gtest.h>

#include <cmath>

#include "algo/atmosphere/SkewT.h"

namespace cg::algo {

namespace {

/// A made-up sounding: 30 C over 20 C at 1000 hPa, cooling 6.5 C/km.
EnvironmentProfile sample(double shiftC = 0.0)
{
    std::vector<ProfileLevel> levels;
    for (double z = 0.0; z <= 16000.0; z += 500.0) {
        const double t = 30.0 + shiftC - 6.5e-3 * std::min(z, 12000.0);
        levels.push_back({z, t, t - 10.0, std::nan(""), 0.0, 0.0});
    }
    levels.front().pressureHPa = 1000.0;
    return EnvironmentProfile(std::move(levels));
}

bool colourAt(const SkewTImage& image, double x, double y, const std::uint8_t* c)
{
    // Within a pixel of where the axes put the point (lines are two pixels wide).
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const long px = std::lround(x) + dx, py = std::lround(y) + dy;
            if (px < 0 || py < 0 || px >= image.width || py >= image.height) continue;
            const std::uint8_t* p =
                &image.rgb[3u * (static_cast<std::size_t>(py) * image.width + px)];
            if (p[0] == c[0] && p[1] == c[1] && p[2] == c[2]) return true;
        }
    return false;
}

}  // namespace

TEST(SkewT, IsothermsLeanFortyFiveDegreesAndPressureIsLogarithmic)
{
    const SkewTAxes a{SkewTOptions{}};
    EXPECT_NEAR(a.y(1050.0), 720.0, 1e-9);
    EXPECT_NEAR(a.y(100.0), 0.0, 1e-9);
    // Equal pressure ratios, equal heights on the page.
    EXPECT_NEAR(a.y(1000.0) - a.y(500.0), a.y(500.0) - a.y(250.0), 1e-9);
    // Along an isotherm: as many columns right as rows up.
    EXPECT_NEAR(a.x(0.0, 500.0) - a.x(0.0, 1000.0), a.y(1000.0) - a.y(500.0), 1e-9);
}

TEST(SkewT, CurvesTicksAndCloudAreWhereTheAxesPutThem)
{
    const EnvironmentProfile profile = sample();
    const ParcelAscent parcel = liftParcel(profile, 0.0);
    SkewTOptions o;
    o.cloudBaseM = parcel.lclM;
    o.cloudTopM = 9000.0;
    const SkewTImage image = drawSkewT(profile, parcel, o);
    ASSERT_EQ(image.rgb.size(), 3u * 640 * 720);
    const SkewTAxes a(o);
    const double p5 = profile.pressure(5000.0);
    EXPECT_TRUE(colourAt(image, a.x(profile.temperature(5000.0), p5), a.y(p5), kSkewTEnvironment));
    EXPECT_TRUE(colourAt(image, a.x(profile.dewpoint(5000.0), p5), a.y(p5), kSkewTDewpoint));
    const ParcelPoint& mid = parcel.path[parcel.path.size() / 3];
    const double pm = profile.pressure(mid.heightM);
    EXPECT_TRUE(colourAt(image, a.x(mid.parcelC, pm), a.y(pm), kSkewTParcel));
    EXPECT_TRUE(colourAt(image, 630, a.y(profile.pressure(parcel.lclM)), kSkewTParcel));
    EXPECT_TRUE(colourAt(image, 595, a.y(profile.pressure(6000.0)), kSkewTCloud));
    EXPECT_FALSE(colourAt(image, 595, a.y(profile.pressure(11000.0)), kSkewTCloud));

    // A sounding 10 C warmer draws its curve 10 C to the right, not where the first one was.
    const EnvironmentProfile warm = sample(10.0);
    const SkewTImage warmer = drawSkewT(warm, parcel, o);
    const double pw = warm.pressure(5000.0);
    EXPECT_TRUE(colourAt(warmer, a.x(warm.temperature(5000.0), pw), a.y(pw), kSkewTEnvironment));
    EXPECT_FALSE(
        colourAt(warmer, a.x(warm.temperature(5000.0) - 10.0, pw), a.y(pw), kSkewTEnvironment));
}

}  // namespace cg::algo
