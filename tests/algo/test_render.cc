// Physics of the volume renderer: Beer-Lambert transmittance, phase-function normalisation,
// sky for missed rays, sun-facing side brighter, independence of the thread count.

#include <gtest/gtest.h>

#include <cmath>

#include "algo/render/image/ToneMap.h"
#include "algo/render/integrators/RenderVolume.h"
#include "algo/render/media/Phase.h"
#include "support/RenderTestVolumes.h"

namespace cg {

using algo::RenderVec3;
using test::luminance;
using test::makeBall;
using test::makeBox;

TEST(RenderPhase, HenyeyGreensteinIntegratesToOne)
{
    // ∫ p dω = 2π ∫_{-1}^{1} p(μ) dμ, Simpson's rule on a fine grid (peaked for g near 1).
    for (const double g : {0.0, 0.3, 0.8, -0.5, 0.95}) {
        const int n = 200000;
        const double h = 2.0 / n;
        double sum = 0.0;
        for (int i = 0; i <= n; ++i) {
            const double mu = -1.0 + i * h;
            const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
            sum += w * algo::henyeyGreenstein(mu, g);
        }
        EXPECT_NEAR(2.0 * M_PI * sum * h / 3.0, 1.0, 1e-6) << "g = " << g;
    }
    EXPECT_DOUBLE_EQ(algo::henyeyGreenstein(0.3, 0.0), 1.0 / (4.0 * M_PI));
}

TEST(RenderPhase, SampledCosinesFollowTheTwoLobeDensity)
{
    // Inverse-CDF samples binned in cos θ against HG's cumulative distribution in μ,
    // P(μ) = (1 − g²) / (2g) (1 / sqrt(1 + g² − 2gμ) − 1 / (1 + g)), blended: a chi-square
    // test, 40 bins, 400,000 stratified samples.
    const double g1 = 0.8, g2 = -0.3, w = 0.2;
    const algo::PhaseFunction phase = algo::PhaseFunction::twoLobeHenyeyGreenstein(g1, g2, w);
    const int bins = 40, n = 400000;
    std::vector<double> count(bins, 0.0);
    for (int i = 0; i < n; ++i) {
        const double u = (i + 0.5) / n;
        const double uLobe = std::fmod(u * 7919.0, 1.0);  // a second, decorrelated coordinate
        int draw = 0;                                     // the lobe first, then the cosine
        const double mu = phase.sample([&] { return draw++ ? u : uLobe; });
        count[std::min(bins - 1, static_cast<int>((mu + 1.0) / 2.0 * bins))] += 1.0;
    }
    double chi2 = 0.0;
    for (int b = 0; b < bins; ++b) {
        const double a = -1.0 + 2.0 * b / bins, c = a + 2.0 / bins;
        const auto cdf = [](double mu, double g) {
            return (1.0 - g * g) / (2.0 * g) *
                   (1.0 / std::sqrt(1.0 + g * g - 2.0 * g * mu) - 1.0 / (1.0 + g));
        };
        const double expected =
            n * ((1.0 - w) * (cdf(c, g1) - cdf(a, g1)) + w * (cdf(c, g2) - cdf(a, g2)));
        chi2 += (count[b] - expected) * (count[b] - expected) / expected;
    }
    EXPECT_LT(chi2, 80.0);  // 39 degrees of freedom: p < 1e-4 above 80
}

TEST(RenderTransmittance, HomogeneousBoxFollowsBeerLambert)
{
    // Voxels 0..39 fill [-0.5, 39.5] voxels: 40 voxels = 20 m per side at 0.5 m voxels.
    const double voxel = 0.5;
    auto box = makeBox(voxel, 40, 0.5f);
    const double sigmaT = 0.1 * 0.5;  // extinction 0.1 /m × density 0.5
    {
        const RenderVec3 o(-30.0, 10.0, 10.0);
        const double T = algo::fogTransmittance(*box, o, RenderVec3(1, 0, 0), 0.1, 0.5);
        const double expected = std::exp(-sigmaT * 20.0);
        EXPECT_NEAR(T / expected, 1.0, 0.01) << T << " vs " << expected;
    }
    {
        // Oblique, crossing the two x faces only: L = 20 m / cos.
        const RenderVec3 dir = RenderVec3(1.0, 0.25, 0.1).unitSafe();
        const RenderVec3 o = RenderVec3(-0.25, 6.0, 8.0) - dir * 50.0;
        const double T = algo::fogTransmittance(*box, o, dir, 0.1, 0.5);
        const double expected = std::exp(-sigmaT * 20.0 / dir.x());
        EXPECT_NEAR(T / expected, 1.0, 0.01) << T << " vs " << expected;
    }
    // A ray that misses the box sees nothing.
    EXPECT_EQ(algo::fogTransmittance(*box, RenderVec3(-30, 40, 10), RenderVec3(1, 0, 0), 0.1, 0.5),
              1.0);
}

TEST(RenderTransmittance, HomogeneousBallFollowsBeerLambert)
{
    // Along an axis through the centre the ball holds voxels -20..20: L = 41 voxels.
    const double voxel = 2.0;
    auto ball = makeBall(voxel, 20, 1.0f);
    for (const double step : {0.25, 0.5, 1.0}) {
        const double T =
            algo::fogTransmittance(*ball, RenderVec3(0, -500, 0), RenderVec3(0, 1, 0), 0.01, step);
        const double expected = std::exp(-0.01 * 41.0 * voxel);
        EXPECT_NEAR(T / expected, 1.0, 0.01) << "step " << step;
    }
}

namespace {

algo::RenderSettings ballScene()
{
    algo::RenderSettings s;
    s.camera.position = RenderVec3(0, -1500, 0);
    s.camera.lookAt = RenderVec3(0, 0, 0);
    s.camera.up = RenderVec3(0, 0, 1);
    s.camera.fovDegrees = 30.0;
    s.camera.width = 64;
    s.camera.height = 48;
    s.ground.enabled = false;
    s.sun.direction = RenderVec3(1, 0, 0);  // from +x: the right half of the image
    s.medium.extinction = 0.05;
    return s;
}

}  // namespace

TEST(RenderImage, MissedRaysSeeTheSkyExactly)
{
    auto ball = makeBall(10.0, 20, 1.0f);  // radius 200 m, about 10 px in this view
    const algo::RenderSettings s = ballScene();
    const algo::RenderedImage img = algo::renderFogVolume(*ball, s);
    ASSERT_EQ(img.rgba.size(), std::size_t(64 * 48 * 4));
    for (const auto& [x, y] : {std::pair{0, 0}, {63, 0}, {0, 47}, {63, 47}, {5, 24}}) {
        const RenderVec3 sky = algo::skyRadiance(s.sky, algo::CameraRays(s.camera).direction(x, y));
        const float* p = &img.rgba[(static_cast<std::size_t>(y) * 64 + x) * 4];
        EXPECT_EQ(p[0], static_cast<float>(sky.x()));
        EXPECT_EQ(p[1], static_cast<float>(sky.y()));
        EXPECT_EQ(p[2], static_cast<float>(sky.z()));
        EXPECT_EQ(p[3], 0.0f);
        // The background is the same sky.
        const float* b = &img.background[(static_cast<std::size_t>(y) * 64 + x) * 3];
        EXPECT_EQ(b[0], p[0]);
        EXPECT_EQ(b[1], p[1]);
        EXPECT_EQ(b[2], p[2]);
    }
    ASSERT_EQ(img.background.size(), std::size_t(64 * 48 * 3));
    // The centre pixel sees the opaque ball.
    EXPECT_GT(img.rgba[(24 * 64 + 32) * 4 + 3], 0.99f);
}

TEST(RenderImage, SunFacingSideIsBrighter)
{
    auto ball = makeBall(10.0, 20, 1.0f);
    algo::RenderSettings s = ballScene();
    s.sky.ambient = 0.0;  // sun light only, so the comparison is about the sun
    const algo::RenderedImage img = algo::renderFogVolume(*ball, s);
    // Ball radius 200 m at 1500 m with a 30° fov over 48 rows: about 13.6 px; probe ±7 px.
    const double lit = luminance(img.rgba, 64, 32 + 7, 24);
    const double dark = luminance(img.rgba, 64, 31 - 7, 24);
    EXPECT_GT(lit, 3.0 * dark) << lit << " vs " << dark;
    EXPECT_GT(lit, 0.0);
}

TEST(RenderImage, IdenticalForOneAndTwoThreads)
{
    auto ball = makeBall(10.0, 20, 0.7f);
    algo::RenderSettings s = ballScene();
    s.ground.enabled = true;
    s.camera.position = RenderVec3(300, -1500, 400);
    s.camera.lookAt = RenderVec3(0, 0, 100);
    s.march.jitter = true;
    const algo::RenderedImage one =
        test::expectSameImageForAnyThreadCount([&] { return algo::renderFogVolume(*ball, s); });
}

TEST(RenderImage, DiffusionKeepsAConservativeCloudUnderAUniformSkyInvisible)
{
    // The white furnace for the fast mode: with albedo 1 and a uniform sky the diffusion
    // solve's answer is a fluence equal to the surroundings' everywhere, with no net flux,
    // so every pixel sees the sky's radiance through the cloud as around it.
    auto ball = makeBall(10.0, 20, 1.0f);
    algo::RenderSettings s = ballScene();
    s.sun.intensity = 0.0;
    s.sky.zenith = s.sky.horizon = RenderVec3(0.4, 0.5, 0.6);
    s.medium.albedo = 1.0;
    s.medium.extinction = 0.025;
    const algo::RenderedImage img = algo::renderFogVolume(*ball, s);
    for (int y = 0; y < 48; y += 3)
        for (int x = 0; x < 64; x += 3)
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(img.rgba[(static_cast<std::size_t>(y) * 64 + x) * 4 + c],
                            s.sky.zenith[c], 2e-3 * s.sky.zenith[c])
                    << x << ", " << y;
    EXPECT_GT(img.rgba[(24 * 64 + 32) * 4 + 3], 0.99f);  // through the opaque centre
    // With the octaves' sky occlusion the centre darkens: the model diffusion replaced.
    s.multiScatter.model = algo::MultiScatterModel::Octaves;
    const algo::RenderedImage octaves = algo::renderFogVolume(*ball, s);
    EXPECT_LT(octaves.rgba[(24 * 64 + 32) * 4 + 1], 0.9 * s.sky.zenith[1]);
}

TEST(RenderImage, RefusesUnusableSettings)
{
    auto ball = makeBall(10.0, 4, 1.0f);
    algo::RenderSettings s = ballScene();
    s.camera.lookAt = s.camera.position;
    EXPECT_THROW(algo::renderFogVolume(*ball, s), std::invalid_argument);
    s = ballScene();
    s.camera.up = RenderVec3(0, 1, 0);  // along the view direction
    EXPECT_THROW(algo::renderFogVolume(*ball, s), std::invalid_argument);
    s = ballScene();
    s.camera.fovDegrees = 180.0;
    EXPECT_THROW(algo::renderFogVolume(*ball, s), std::invalid_argument);
}

TEST(RenderToneMap, CurvesAreMonotoneAndBounded)
{
    for (const auto curve :
         {algo::ToneCurve::Aces, algo::ToneCurve::Hable, algo::ToneCurve::Clamp}) {
        double prev = 0.0;
        for (double x = 0.0; x < 50.0; x += 0.01) {
            const double y = algo::toneMap(x, curve);
            EXPECT_GE(y, prev);
            EXPECT_LE(y, 1.0);
            prev = y;
        }
        EXPECT_EQ(algo::toneMap(std::nan(""), curve), 0.0);
    }
    for (double v = 0.0; v <= 1.0; v += 0.01)
        EXPECT_NEAR(algo::srgbDecode(algo::srgbEncode(v)), v, 1e-12);
    EXPECT_NEAR(algo::srgbEncode(0.5), 0.7353569830524495, 1e-12);
}

}  // namespace cg
