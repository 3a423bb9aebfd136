// The reference path tracer against closed forms: Beer-Lambert transmittance and single
// scattering in a homogeneous slab, the white furnace (a conservative cloud under a uniform
// sky is invisible), the ground under an empty sky; each checked as an unbiased estimate, its
// mean error within a few standard errors. And the same image for any thread count.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>

#include "algo/render/integrators/RenderPathTrace.h"
#include "algo/render/media/Phase.h"
#include "support/RenderTestVolumes.h"

namespace cg {

namespace {

using algo::RenderVec3;

/// Mean and standard error of per-pixel residuals (estimate − exact) over a pixel window.
struct Residual {
    double mean = 0.0;
    double standardError = 0.0;
    double meanExact = 0.0;
};

Residual residualOver(int x0, int y0, int x1, int y1,
                      const std::function<double(int, int)>& estimate,
                      const std::function<double(int, int)>& exact)
{
    double sum = 0.0, sum2 = 0.0, sumExact = 0.0;
    int n = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const double r = estimate(x, y) - exact(x, y);
            sum += r;
            sum2 += r * r;
            sumExact += exact(x, y);
            ++n;
        }
    Residual out;
    out.mean = sum / n;
    out.standardError = std::sqrt(std::max(0.0, sum2 / n - out.mean * out.mean) / (n - 1));
    out.meanExact = sumExact / n;
    return out;
}

/// A slab 640 m wide and `layers` 10 m voxels thick, seen from 5 km straight below through a
/// 1° field of view: every pixel's ray crosses only its top and bottom faces.
struct SlabScene {
    openvdb::FloatGrid::Ptr grid;
    algo::RenderSettings s;

    explicit SlabScene(int layers)
        : grid(test::makeBox(10.0, openvdb::Coord(0, 0, 0), openvdb::Coord(63, 63, layers - 1),
                             1.0f))
    {
        s.camera.position = RenderVec3(315, 315, -5000);
        s.camera.lookAt = RenderVec3(315, 315, 0);
        s.camera.up = RenderVec3(0, 1, 0);
        s.camera.fovDegrees = 1.0;
        s.camera.width = 16;
        s.camera.height = 16;
        s.ground.enabled = false;
        s.medium.extinction = 0.01;  // × 10 m × layers: optical depth = layers / 10
        s.pathTrace.samples = 64;
    }

    double pixel(const algo::RenderedImage& img, int x, int y, int channel) const
    {
        return img.rgba[(static_cast<std::size_t>(y) * img.width + x) * 4 + channel];
    }

    RenderVec3 direction(int x, int y) const { return algo::CameraRays(s.camera).direction(x, y); }
};

}  // namespace

TEST(RenderPathTrace, SlabTransmittanceFollowsBeerLambert)
{
    SlabScene scene(20);  // τ = 2 straight up
    scene.s.sun.intensity = 0.0;
    scene.s.sky.ambient = 0.0;  // the slab scatters no light: it only dims the sky behind it
    scene.s.sky.zenith = scene.s.sky.horizon = RenderVec3(1.0);
    scene.s.pathTrace.samples = 1024;  // each estimate is nearly binary in a uniform slab
    const algo::RenderedImage img = algo::renderPathTraced(*scene.grid, scene.s);
    const Residual r = residualOver(
        0, 0, 16, 16, [&](int x, int y) { return 1.0 - scene.pixel(img, x, y, 3); },
        [&](int x, int y) { return std::exp(-2.0 / scene.direction(x, y).z()); });
    EXPECT_LT(std::abs(r.mean), 4.0 * r.standardError + 1e-6)
        << r.mean << " +- " << r.standardError << " of " << r.meanExact;
    EXPECT_LT(std::abs(r.mean) / r.meanExact, 0.01);
    EXPECT_NEAR(r.meanExact, std::exp(-2.0), 1e-3);
    // Beauty = T × sky.
    for (int x = 0; x < 16; ++x)
        EXPECT_FLOAT_EQ(scene.pixel(img, x, 7, 0), 1.0f - scene.pixel(img, x, 7, 3));
}

TEST(RenderPathTrace, SlabSingleScatteringMatchesTheClosedForm)
{
    // One scattering event (maxBounces 1), a black sky: what reaches the camera is sun light
    // scattered once. With τ the optical depth above the slab's bottom and μ_v, μ_s the
    // cosines of the view ray and the sun from the vertical:
    //   L = a p(cos θ) E / μ_v ∫_0^τ exp(−u / μ_v − (τ − u) / μ_s) du,
    // whatever the slab's density profile (it only reparametrises u).
    // Both phase functions: the Mie fit's sharp lobe is evaluated as the closed form's.
    for (const auto model : {algo::PhaseModel::TwoLobeHenyeyGreenstein, algo::PhaseModel::Mie}) {
        SlabScene scene(10);  // τ = 1
        algo::RenderSettings& s = scene.s;
        s.medium.phase = model;
        SCOPED_TRACE(model == algo::PhaseModel::Mie ? "mie" : "twoLobeHG");
        s.pathTrace.maxBounces = 1;
        s.pathTrace.samples = 256;
        s.sky.zenith = s.sky.horizon = RenderVec3(0.0);
        s.sun.direction = RenderVec3(0.5, 0.0, std::sqrt(0.75));  // 30° from the zenith
        s.sun.colour = RenderVec3(1.0);
        s.sun.intensity = 3.0;
        s.medium.albedo = 0.9;
        const algo::RenderedImage img = algo::renderPathTraced(*scene.grid, s);
        const double tau = 1.0;
        const auto exact = [&](int x, int y) {
            const RenderVec3 v = scene.direction(x, y);
            const double mv = v.z(), ms = s.sun.direction.unitSafe().z();
            const double k = 1.0 / mv - 1.0 / ms;
            const double integral = std::exp(-tau / ms) * (1.0 - std::exp(-k * tau)) / k;
            const double phase = algo::phaseOf(s.medium)(s.sun.direction.unitSafe().dot(v));
            return s.medium.albedo * phase * s.sun.intensity / mv * integral;
        };
        const Residual r = residualOver(
            0, 0, 16, 16, [&](int x, int y) { return scene.pixel(img, x, y, 1); }, exact);
        EXPECT_LT(std::abs(r.mean), 4.0 * r.standardError + 1e-6)
            << r.mean << " +- " << r.standardError << " of " << r.meanExact;
        EXPECT_LT(std::abs(r.mean) / r.meanExact, 0.02);
    }
}

TEST(RenderPathTrace, ConservativeCloudUnderAUniformSkyIsInvisible)
{
    // The white furnace: albedo 1, no sun, no ground, the same radiance from every direction.
    // Every path ends on the sky, so every pixel sees the sky's radiance, through the cloud
    // (optical diameter 10: dozens of events a path) as around it.
    auto ball = test::makeBall(10.0, 20, 1.0f);
    algo::RenderSettings s;
    s.camera.position = RenderVec3(0, -1500, 0);
    s.camera.lookAt = RenderVec3(0, 0, 0);
    s.camera.up = RenderVec3(0, 0, 1);
    s.camera.fovDegrees = 12.0;
    s.camera.width = 12;
    s.camera.height = 12;
    s.ground.enabled = false;
    s.sun.intensity = 0.0;
    s.sky.zenith = s.sky.horizon = RenderVec3(0.4, 0.5, 0.6);
    s.sky.ambient = 1.0;
    s.medium.albedo = 1.0;
    s.medium.extinction = 0.025;
    s.pathTrace.samples = 32;
    const algo::RenderedImage img = algo::renderPathTraced(*ball, s);
    for (int c = 0; c < 3; ++c) {
        const double sky = s.sky.zenith[c];
        const Residual r = residualOver(
            2, 2, 10, 10,
            [&](int x, int y) { return img.rgba[(static_cast<std::size_t>(y) * 12 + x) * 4 + c]; },
            [&](int, int) { return sky; });
        EXPECT_LT(std::abs(r.mean), 4.0 * r.standardError + 1e-6) << "channel " << c;
        EXPECT_LT(std::abs(r.mean) / sky, 0.02) << "channel " << c;
    }
    // The window is all cloud: the centre pixel's ray crosses 10 optical depths.
    EXPECT_GT(img.rgba[(6 * 12 + 6) * 4 + 3], 0.99f);
}

TEST(RenderPathTrace, EmptyVolumeShowsTheSkyAndTheLitGround)
{
    // Nothing to scatter: rays above the horizon see the sky exactly; the ground reflects the
    // sun, E μ_s / π, and the sky, whose irradiance is π (0.2 horizon + 0.8 zenith), times
    // its albedo, faded by the haze.
    auto empty = test::makeFogGrid(10.0);
    algo::RenderSettings s;
    s.camera.position = RenderVec3(0, -2000, 300);
    s.camera.lookAt = RenderVec3(0, 0, 300);
    s.camera.width = 24;
    s.camera.height = 24;
    s.pathTrace.samples = 32;
    const algo::RenderedImage img = algo::renderPathTraced(*empty, s);
    const algo::CameraRays rays(s.camera);
    const RenderVec3 sun = s.sun.direction.unitSafe();
    const RenderVec3 lit =
        s.ground.albedo * (s.sun.colour * s.sun.intensity * (sun.z() / M_PI) +
                           (s.sky.horizon * 0.2 + s.sky.zenith * 0.8) * s.sky.ambient);
    const auto groundExact = [&](int x, int y, int c) {
        const RenderVec3 d = rays.direction(x, y);
        return algo::hazedGround(s, lit, algo::groundDistance(s.ground, s.camera.position, d))[c];
    };
    for (int c = 0; c < 3; ++c) {
        // The rows below the horizon (the camera looks level: the lower half).
        const Residual r = residualOver(
            0, 14, 24, 24,
            [&](int x, int y) { return img.rgba[(static_cast<std::size_t>(y) * 24 + x) * 4 + c]; },
            [&](int x, int y) { return groundExact(x, y, c); });
        EXPECT_LT(std::abs(r.mean), 4.0 * r.standardError + 1e-6) << "channel " << c;
        EXPECT_LT(std::abs(r.mean) / r.meanExact, 0.02) << "channel " << c;
    }
    for (int x = 0; x < 24; ++x) {
        const RenderVec3 sky = algo::skyRadiance(s.sky, rays.direction(x, 3));
        const float* p = &img.rgba[(3 * 24 + static_cast<std::size_t>(x)) * 4];
        EXPECT_EQ(p[0], static_cast<float>(sky.x()));
        EXPECT_EQ(p[2], static_cast<float>(sky.z()));
        EXPECT_EQ(p[3], 0.0f);
    }
}

TEST(RenderPathTrace, IdenticalForOneAndTwoThreads)
{
    auto ball = test::makeBall(10.0, 12, 0.8f);
    algo::RenderSettings s;
    s.camera.position = RenderVec3(300, -1500, 400);
    s.camera.lookAt = RenderVec3(0, 0, 100);
    s.camera.width = 20;
    s.camera.height = 16;
    s.pathTrace.samples = 4;
    const algo::RenderedImage one =
        test::expectSameImageForAnyThreadCount([&] { return algo::renderPathTraced(*ball, s); });
    // A different seed gives different noise.
    s.march.seed = 1;
    const algo::RenderedImage other = algo::renderPathTraced(*ball, s);
    EXPECT_NE(std::memcmp(one.rgba.data(), other.rgba.data(), one.rgba.size() * sizeof(float)), 0);
}

TEST(RenderPathTrace, RefusesUnusableSettings)
{
    auto ball = test::makeBall(10.0, 4, 1.0f);
    algo::RenderSettings s;
    s.pathTrace.samples = 0;
    EXPECT_THROW(algo::renderPathTraced(*ball, s), std::invalid_argument);
    s = algo::RenderSettings();
    s.pathTrace.maxBounces = 0;
    EXPECT_THROW(algo::renderPathTraced(*ball, s), std::invalid_argument);
    s = algo::RenderSettings();
    s.camera.lookAt = s.camera.position;
    EXPECT_THROW(algo::renderPathTraced(*ball, s), std::invalid_argument);
}

}  // namespace cg
