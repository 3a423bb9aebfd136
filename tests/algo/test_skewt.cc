// The skew-T diagram: each curve and reference line where the axes put it, the isotherms at 45
// degrees and labelled, CAPE and CIN shaded where the parcel is warmer or colder, the parcel's
// levels as ticks, a cloud's extent as a bar and wind barbs only where there is wind.

#include <gtest/gtest.h>

#include <cmath>

#include "algo/atmosphere/SkewT.h"
#include "algo/atmosphere/SkewTCanvas.h"
#include "algo/atmosphere/SkewTLayers.h"
#include "algo/atmosphere/Thermodynamics.h"

namespace cg::algo {

namespace {

/// A made-up sounding: 30 C over 20 C at 1000 hPa, cooling 6.5 C/km, with a west wind of
/// `windMs` above `windFromM` and calm air below.
EnvironmentProfile sample(double shiftC = 0.0, double windMs = 0.0, double windFromM = 0.0)
{
    std::vector<ProfileLevel> levels;
    for (double z = 0.0; z <= 16000.0; z += 500.0) {
        const double t = 30.0 + shiftC - 6.5e-3 * std::min(z, 12000.0);
        const double wind = z >= windFromM ? windMs : 0.0;
        levels.push_back({z, t, t - 10.0, std::nan(""), wind, 0.0});
    }
    levels.front().pressureHPa = 1000.0;
    return EnvironmentProfile(std::move(levels));
}

const std::uint8_t* pixel(const SkewTImage& image, long x, long y)
{
    return &image.rgb[3u * (static_cast<std::size_t>(y) * image.width + x)];
}

bool colourAt(const SkewTImage& image, double x, double y, const std::uint8_t* c, int reach = 1)
{
    // Within `reach` pixels of where the axes put the point (lines are two pixels wide).
    for (int dy = -reach; dy <= reach; ++dy)
        for (int dx = -reach; dx <= reach; ++dx) {
            const long px = std::lround(x) + dx, py = std::lround(y) + dy;
            if (px < 0 || py < 0 || px >= image.width || py >= image.height) continue;
            const std::uint8_t* p = pixel(image, px, py);
            if (p[0] == c[0] && p[1] == c[1] && p[2] == c[2]) return true;
        }
    return false;
}

/// Pixels of colour c in the rectangle from (x0, y0) to (x1, y1) inclusive.
int countColour(const SkewTImage& image, int x0, int y0, int x1, int y1, const std::uint8_t* c)
{
    int n = 0;
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
            const std::uint8_t* p = pixel(image, x, y);
            n += p[0] == c[0] && p[1] == c[1] && p[2] == c[2];
        }
    return n;
}

}  // namespace

TEST(SkewT, IsothermsLeanFortyFiveDegreesAndPressureIsLogarithmic)
{
    const SkewTAxes a{SkewTOptions{}};
    EXPECT_NEAR(a.y(1050.0), a.bottom(), 1e-9);
    EXPECT_NEAR(a.y(100.0), a.top(), 1e-9);
    EXPECT_NEAR(a.x(-40.0, 1050.0), a.left(), 1e-9);
    EXPECT_NEAR(a.x(50.0, 1050.0), a.right(), 1e-9);
    // Equal pressure ratios, equal heights on the page.
    EXPECT_NEAR(a.y(1000.0) - a.y(500.0), a.y(500.0) - a.y(250.0), 1e-9);
    // Along an isotherm: as many columns right as rows up.
    EXPECT_NEAR(a.x(0.0, 500.0) - a.x(0.0, 1000.0), a.y(1000.0) - a.y(500.0), 1e-9);
    // The inverses.
    EXPECT_NEAR(a.pressure(a.y(700.0)), 700.0, 1e-9);
    EXPECT_NEAR(a.temperature(a.x(-12.0, 400.0), 400.0), -12.0, 1e-9);
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
    EXPECT_TRUE(colourAt(image, a.right() - 5, a.y(profile.pressure(parcel.lclM)), kSkewTParcel));
    EXPECT_TRUE(colourAt(image, a.right() - 76, a.y(profile.pressure(6000.0)), kSkewTCloud));
    EXPECT_FALSE(colourAt(image, a.right() - 76, a.y(profile.pressure(11000.0)), kSkewTCloud));

    // A sounding 10 C warmer draws its curve 10 C to the right, not where the first one was.
    const EnvironmentProfile warm = sample(10.0);
    const SkewTImage warmer = drawSkewT(warm, liftParcel(warm, 0.0), SkewTOptions{});
    const double pw = warm.pressure(5000.0);
    EXPECT_TRUE(colourAt(warmer, a.x(warm.temperature(5000.0), pw), a.y(pw), kSkewTEnvironment));
    EXPECT_FALSE(
        colourAt(warmer, a.x(warm.temperature(5000.0) - 10.0, pw), a.y(pw), kSkewTEnvironment));
}

TEST(SkewT, CapeIsShadedBetweenParcelAndEnvironmentAboveTheLfcAndCinBelowIt)
{
    // A surface parcel 3 C warmer than its air: free convection from low down, CAPE above.
    const EnvironmentProfile profile = sample();
    const ParcelAscent parcel = liftParcel(profile, 0.0, 31.0, 24.0);
    ASSERT_TRUE(std::isfinite(parcel.lfcM));
    ASSERT_GT(parcel.capeJPerKg, 100.0);
    const SkewTOptions o;
    const SkewTAxes a(o);
    const SkewTImage image = drawSkewT(profile, parcel, o);
    // Halfway between the parcel and the environment, a third of the way from the LFC to the EL.
    const ParcelPoint* q = nullptr;
    for (const ParcelPoint& p : parcel.path)
        if (p.heightM >= parcel.lfcM + (parcel.elM - parcel.lfcM) / 3.0) {
            q = &p;
            break;
        }
    ASSERT_NE(q, nullptr);
    ASSERT_GT(q->parcelC - q->environmentC, 2.0);
    const double p = profile.pressure(q->heightM);
    const double inside = a.x(0.5 * (q->parcelC + q->environmentC), p);
    EXPECT_TRUE(colourAt(image, inside, a.y(p), kSkewTCape, 2));
    EXPECT_FALSE(colourAt(image, inside, a.y(p), kSkewTCin, 2));
    // Left of the parcel's curve and right of the environment's: not shaded.
    EXPECT_FALSE(colourAt(image, a.x(q->parcelC + 4.0, p), a.y(p), kSkewTCape, 2));
    EXPECT_FALSE(colourAt(image, a.x(q->environmentC - 4.0, p), a.y(p), kSkewTCape, 2));
    // Above the EL nothing is shaded as CAPE.
    const double pTop = profile.pressure(parcel.elM + 1500.0);
    const double xTop =
        a.x(0.5 * (profile.temperature(parcel.elM + 1500.0) + parcel.path.back().parcelC), pTop);
    EXPECT_FALSE(colourAt(image, xTop, a.y(pTop), kSkewTCape, 2));

    // Without a warm start the parcel from the ground is colder than its air up to its LFC:
    // the CIN, shaded blue between the two curves below the LFC.
    const ParcelAscent plain = liftParcel(profile, 0.0);
    ASSERT_TRUE(std::isfinite(plain.lfcM));
    ASSERT_LT(plain.cinJPerKg, -1.0);
    const SkewTImage cin = drawSkewT(profile, plain, o);
    int blue = 0, red = 0;
    for (const ParcelPoint& pt : plain.path) {
        if (pt.heightM >= plain.lfcM) break;
        if (pt.environmentC - pt.parcelC < 1.0) continue;
        const double pp = profile.pressure(pt.heightM);
        const double xm = a.x(0.5 * (pt.parcelC + pt.environmentC), pp);
        blue += colourAt(cin, xm, a.y(pp), kSkewTCin, 0);
        red += colourAt(cin, xm, a.y(pp), kSkewTCape, 0);
    }
    EXPECT_GT(blue, 0);
    EXPECT_EQ(red, 0);
}

TEST(SkewT, DryAndMoistAdiabatsFollowTheirPhysics)
{
    // Through a standard atmosphere far to the right of the adiabats checked.
    const EnvironmentProfile profile = sample(20.0);
    const ParcelAscent parcel = liftParcel(profile, 0.0);
    const SkewTOptions o;
    const SkewTAxes a(o);
    const SkewTImage image = drawSkewT(profile, parcel, o);
    // The dry adiabat through 1000 hPa, 20 C: theta = 293.15 K.
    const double kappa = thermo::kDryGasConstant / thermo::kDryHeatCapacity;
    const double t500 = 293.15 * std::pow(0.5, kappa) - thermo::kKelvin;
    EXPECT_NEAR(t500, -32.7, 0.2);
    EXPECT_TRUE(colourAt(image, a.x(t500, 500.0), a.y(500.0), kSkewTDryAdiabat));
    EXPECT_FALSE(colourAt(image, a.x(t500 + 4.0, 500.0), a.y(500.0), kSkewTDryAdiabat));
    // The saturated adiabat through 1000 hPa, 20 C keeps its equivalent potential temperature
    // theta_e ~ theta exp(L r_s / (c_pd T)) (about 332 K) while it cools: within the few kelvin
    // this approximation drifts, where the dry adiabat's would be 40 K off at 500 hPa.
    const auto thetaE = [&](double c, double p) {
        const double t = c + thermo::kKelvin;
        return t * std::pow(1000.0 / p, kappa) *
               std::exp(thermo::kLatentHeat * thermo::saturationMixingRatio(c, p) /
                        (thermo::kDryHeatCapacity * t));
    };
    for (double p : {850.0, 500.0, 300.0})
        EXPECT_NEAR(thetaE(skewt::moistAdiabatTemperature(20.0, p), p), thetaE(20.0, 1000.0), 4.0)
            << p << " hPa";
    EXPECT_NEAR(skewt::moistAdiabatTemperature(20.0, 1000.0), 20.0, 1e-12);
    // Dashed, so somewhere within a few pixels along the line.
    bool found = false;
    for (double p = 490.0; p <= 510.0 && !found; p += 1.0)
        found = colourAt(image, a.x(skewt::moistAdiabatTemperature(20.0, p), p), a.y(p),
                         kSkewTMoistAdiabat);
    EXPECT_TRUE(found);
}

TEST(SkewT, IsothermsAreLabelledOnTheTemperatureAxis)
{
    const EnvironmentProfile profile = sample();
    const ParcelAscent parcel = liftParcel(profile, 0.0);
    const SkewTOptions o;
    const SkewTAxes a(o);
    const SkewTImage image = drawSkewT(profile, parcel, o);
    // "-20" is drawn centred under the -20 C isotherm, glyph for glyph.
    SkewTCanvas expected(o.width, o.height);
    const int w = SkewTCanvas::textWidth("-20");
    const int x0 = static_cast<int>(std::lround(a.x(-20.0, o.bottomHPa))) - w / 2;
    const int y0 = a.bottom() + 5;
    expected.text("-20", x0, y0, kSkewTText);
    const SkewTImage glyphs = expected.take();
    int ink = 0, mismatched = 0;
    for (int y = y0; y < y0 + SkewTCanvas::kGlyphHeight; ++y)
        for (int x = x0; x < x0 + w; ++x) {
            const bool want = pixel(glyphs, x, y)[0] == kSkewTText[0];
            const bool got = pixel(image, x, y)[0] == kSkewTText[0];
            ink += want;
            mismatched += want != got;
        }
    EXPECT_GT(ink, 10);
    EXPECT_EQ(mismatched, 0);
    // Halfway between two isotherms the axis has no label.
    const int xm = static_cast<int>(std::lround(a.x(-15.0, o.bottomHPa)));
    EXPECT_EQ(countColour(image, xm - 2, y0, xm + 2, y0 + 6, kSkewTText), 0);
}

TEST(SkewT, WindBarbsAreDrawnOnlyWhereTheProfileHasWind)
{
    // Calm below 5 km, 25 m/s (about 50 kt) from the west above 5.5 km.
    const EnvironmentProfile profile = sample(0.0, 25.0, 5500.0);
    const ParcelAscent parcel = liftParcel(profile, 0.0);
    const SkewTOptions o;
    const SkewTAxes a(o);
    const SkewTImage image = drawSkewT(profile, parcel, o);
    const int yCalm = static_cast<int>(a.y(profile.pressure(4500.0)));
    const int yWindy = static_cast<int>(a.y(profile.pressure(7000.0)));
    EXPECT_EQ(countColour(image, a.right() + 1, yCalm, o.width - 1, a.bottom() - 1, kSkewTBarb), 0);
    EXPECT_GT(countColour(image, a.right() + 1, a.top(), o.width - 1, yWindy, kSkewTBarb), 50);
    // No wind at all: no barbs.
    const SkewTImage calm = drawSkewT(sample(), parcel, o);
    EXPECT_EQ(countColour(calm, a.right() + 1, 0, o.width - 1, o.height - 1, kSkewTBarb), 0);
}

TEST(SkewT, NoBarbsAboveTheHighestMeasuredWind)
{
    // 25 m/s measured up to 6 km, no wind given above: the profile holds it above (that is
    // what it interpolates with), but the diagram draws nothing nobody measured.
    std::vector<ProfileLevel> levels;
    for (double z = 0.0; z <= 16000.0; z += 500.0) {
        const double t = 30.0 - 6.5e-3 * std::min(z, 12000.0);
        const double wind = z <= 6000.0 ? 25.0 : std::nan("");
        levels.push_back({z, t, t - 10.0, std::nan(""), wind, wind == wind ? 0.0 : wind});
    }
    levels.front().pressureHPa = 1000.0;
    const EnvironmentProfile profile(std::move(levels));
    EXPECT_EQ(profile.windTopHeight(), 6000.0);
    EXPECT_EQ(profile.wind(9000.0).east, 25.0);  // held, for the physics
    const SkewTOptions o;
    const SkewTAxes a(o);
    const SkewTImage image = drawSkewT(profile, liftParcel(profile, 0.0), o);
    const int yTop = static_cast<int>(a.y(profile.pressure(6000.0))) - 12;  // a barb's reach
    EXPECT_EQ(countColour(image, a.right() + 1, a.top(), o.width - 1, yTop, kSkewTBarb), 0);
    EXPECT_GT(countColour(image, a.right() + 1, yTop, o.width - 1, a.bottom() - 1, kSkewTBarb), 50);
    // A profile as stored keeps it; a top that is no level is refused.
    const EnvironmentProfile stored(profile.levels(), profile.windTopHeight());
    EXPECT_EQ(stored.windTopHeight(), 6000.0);
    EXPECT_THROW(EnvironmentProfile(profile.levels(), 6100.0), std::invalid_argument);
}

TEST(SkewT, AWestWindBarbPointsWestWithItsFeathersUp)
{
    SkewTCanvas canvas(60, 60);
    // 15 m/s from the west: about 29 kt, three barbs.
    skewt::drawWindBarb(canvas, {40.0, 30.0}, Wind{15.0, 0.0});
    const SkewTImage image = canvas.take();
    EXPECT_GT(countColour(image, 14, 28, 38, 32, kSkewTBarb), 20);  // the staff, westward
    EXPECT_GT(countColour(image, 14, 18, 30, 27, kSkewTBarb), 6);   // feathers above it
    EXPECT_EQ(countColour(image, 0, 33, 59, 59, kSkewTBarb), 0);    // none below
    EXPECT_EQ(countColour(image, 43, 0, 59, 59, kSkewTBarb), 0);    // none east of the station
}

}  // namespace cg::algo
