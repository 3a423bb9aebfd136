#include "algo/render/integrators/RenderPathTrace.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "algo/CounterRandom.h"
#include "algo/render/RenderRays.h"
#include "algo/render/media/Phase.h"
#include "algo/render/media/RenderOccupancy.h"
#include "algo/render/media/TrilinearDensity.h"

namespace cg::algo {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::uint64_t kPathStream = 0x5061746854726163ull;  // "PathTrac"
/// Russian roulette on a shadow ray's transmittance below this (kept unbiased by reweighting).
constexpr double kShadowRoulette = 0.05;
/// Paths are never ended by roulette before this many events (the first bounces carry most
/// of the light and cost little).
constexpr int kPathRouletteAfter = 4;

/// SplitMix64 from a per-path key: a pure function of (seed, pixel, sample).
class PathRandom {
public:
    explicit PathRandom(std::uint64_t key) : mState(key) {}

    double uniform()
    {
        const std::uint64_t bits = mix64(mState);
        mState += 0x9e3779b97f4a7c15ull;
        return static_cast<double>(bits >> 11) * 0x1.0p-53;
    }

    /// An exponential free-flight distance for rate `rate` (> 0).
    double exponential(double rate) { return -std::log1p(-uniform()) / rate; }

private:
    std::uint64_t mState;
};

/// A unit vector with polar cosine `cosTheta` about unit `axis` and azimuth `phi`.
RenderVec3 aroundAxis(const RenderVec3& axis, double cosTheta, double phi)
{
    const RenderVec3 helper = std::abs(axis.x()) < 0.9 ? RenderVec3(1, 0, 0) : RenderVec3(0, 1, 0);
    const RenderVec3 u = axis.cross(helper).unitSafe();
    const RenderVec3 v = axis.cross(u);
    const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
    return (u * (sinTheta * std::cos(phi)) + v * (sinTheta * std::sin(phi)) + axis * cosTheta)
        .unitSafe();
}

class PathTracer {
public:
    PathTracer(const openvdb::FloatGrid& grid, const RenderSettings& settings)
        : mS(settings),
          mGrid(grid),
          mOcc(grid.tree(), /*majorants=*/true),
          mRays(settings.camera),
          mPhase(phaseOf(settings.medium))
    {
        renderVoxelSize(grid);  // refuses a non-linear transform
        if (settings.pathTrace.samples < 1 || settings.pathTrace.maxBounces < 1)
            throw std::invalid_argument("samples and maxBounces must be at least 1");
        if (!(settings.sun.direction.length() > 0.0))
            throw std::invalid_argument("sun direction is zero");
        mSunDir = settings.sun.direction.unitSafe();
        mSunIrradiance = settings.sun.colour * settings.sun.intensity;
        mSunOn = settings.sun.intensity > 0.0 && !(settings.ground.enabled && mSunDir.z() <= 0.0);
        mExtinction = std::max(0.0, settings.medium.extinction);
    }

    const RenderOccupancy& occupancy() const { return mOcc; }

    /// Mean over the pixel's paths of beauty, transmittance and background.
    void pixel(int px, int py, TrilinearDensity& density, float* rgba, float* background) const
    {
        const RenderVec3 dir = mRays.direction(px, py);
        const RenderVec3& origin = mS.camera.position;
        const double tGround = groundDistance(mS.ground, origin, dir);
        const std::uint64_t pixelIndex =
            static_cast<std::uint64_t>(py) * static_cast<std::uint64_t>(mS.camera.width) +
            static_cast<std::uint64_t>(px);
        const std::uint64_t pixelKey = counterBits(mS.march.seed, kPathStream, pixelIndex);

        RenderVec3 cloud(0.0), behind(0.0);
        double transmittance = 0.0;
        const int n = mS.pathTrace.samples;
        for (int s = 0; s < n; ++s) {
            PathRandom rng(mix64(pixelKey ^ static_cast<std::uint64_t>(s)));
            transmittance += this->transmittance(density, origin, dir, tGround, rng);
            const double tHit = freeFlight(density, origin, dir, tGround, rng);
            if (std::isfinite(tHit))
                cloud += pathRadiance(density, origin + dir * tHit, dir, true, rng);
            if (std::isfinite(tGround)) {
                const RenderVec3 ground = origin + dir * tGround;
                behind += hazedGround(mS, pathRadiance(density, ground, dir, false, rng), tGround);
            }
        }
        const double inv = 1.0 / n;
        cloud *= inv;
        transmittance *= inv;
        const RenderVec3 back = std::isfinite(tGround) ? behind * inv : skyRadiance(mS.sky, dir);
        // Beauty = cloud + T × background: both factors are independent unbiased means.
        const RenderVec3 beauty = cloud + back * transmittance;
        rgba[0] = static_cast<float>(beauty.x());
        rgba[1] = static_cast<float>(beauty.y());
        rgba[2] = static_cast<float>(beauty.z());
        rgba[3] = static_cast<float>(1.0 - transmittance);
        background[0] = static_cast<float>(back.x());
        background[1] = static_cast<float>(back.y());
        background[2] = static_cast<float>(back.z());
    }

private:
    double sigmaT(TrilinearDensity& density, const RenderVec3& indexPoint) const
    {
        const double d = density.sample(indexPoint);
        return d > 0.0 ? mExtinction * d : 0.0;
    }

    /// The block's majorant of σ_t, 1/m (a hair above the largest sample, for rounding).
    double majorant(std::size_t block) const
    {
        return mExtinction * double(mOcc.majorant(block)) * (1.0 + 1e-6);
    }

    /// Delta tracking: the distance to the first real collision along the ray before tMax,
    /// or +infinity if the ray gets through.
    double freeFlight(TrilinearDensity& density, const RenderVec3& origin, const RenderVec3& dir,
                      double tMax, PathRandom& rng) const
    {
        const IndexRay ray = toIndexRay(mGrid.transform(), origin, dir);
        double hit = kInf;
        mOcc.walk(ray.o, ray.d, 0.0, tMax, [&](std::size_t block, double t0, double t1) {
            const double rate = majorant(block);
            if (!(rate > 0.0)) return true;
            for (double t = t0 + rng.exponential(rate); t < t1; t += rng.exponential(rate)) {
                if (rng.uniform() * rate < sigmaT(density, ray.o + ray.d * t)) {
                    hit = t;
                    return false;
                }
            }
            return true;
        });
        return hit;
    }

    /// Ratio tracking with Russian roulette: an unbiased estimate of exp(−∫ σ_t) to tMax.
    double transmittance(TrilinearDensity& density, const RenderVec3& origin, const RenderVec3& dir,
                         double tMax, PathRandom& rng) const
    {
        const IndexRay ray = toIndexRay(mGrid.transform(), origin, dir);
        double T = 1.0;
        mOcc.walk(ray.o, ray.d, 0.0, tMax, [&](std::size_t block, double t0, double t1) {
            const double rate = majorant(block);
            if (!(rate > 0.0)) return true;
            for (double t = t0 + rng.exponential(rate); t < t1; t += rng.exponential(rate)) {
                T *= std::max(0.0, 1.0 - sigmaT(density, ray.o + ray.d * t) / rate);
                if (T < kShadowRoulette) {
                    if (rng.uniform() * kShadowRoulette >= T) {
                        T = 0.0;
                        return false;
                    }
                    T = kShadowRoulette;
                }
            }
            return true;
        });
        return T;
    }

    /// Sun light reaching point p (irradiance times transmittance), or 0 below the horizon.
    double sunVisibility(TrilinearDensity& density, const RenderVec3& p, PathRandom& rng) const
    {
        return mSunOn ? transmittance(density, p, mSunDir, kInf, rng) : 0.0;
    }

    /// Radiance arriving along −dir at vertex x: a scattering event in the medium
    /// (`inMedium`) or a point on the ground, and every event of the path that follows.
    RenderVec3 pathRadiance(TrilinearDensity& density, RenderVec3 x, RenderVec3 dir, bool inMedium,
                            PathRandom& rng) const
    {
        const RenderMedium& m = mS.medium;
        RenderVec3 L(0.0), beta(1.0);
        for (int event = 0; event < mS.pathTrace.maxBounces; ++event) {
            if (inMedium) {
                beta *= m.albedo;
                if (mSunOn) {
                    L += beta * mSunIrradiance *
                         (mPhase(mSunDir.dot(dir)) * sunVisibility(density, x, rng));
                }
                const double cosTheta = mPhase.sample([&] { return rng.uniform(); });
                dir = aroundAxis(dir, cosTheta, 2.0 * kPi * rng.uniform());
            } else {
                x = RenderVec3(x.x(), x.y(), 0.0);
                if (mSunOn && mSunDir.z() > 0.0)
                    L += beta * mS.ground.albedo * mSunIrradiance *
                         (mSunDir.z() / kPi * sunVisibility(density, x, rng));
                beta *= mS.ground.albedo;
                // Cosine-weighted bounce: albedo × cos / π over pdf cos / π leaves the albedo.
                const double u = rng.uniform();
                dir =
                    aroundAxis(RenderVec3(0, 0, 1), std::sqrt(1.0 - u), 2.0 * kPi * rng.uniform());
            }
            if (event >= kPathRouletteAfter) {
                const double q = std::max({beta.x(), beta.y(), beta.z()});
                if (q < 1.0) {
                    if (!(rng.uniform() < q)) break;
                    beta *= 1.0 / q;
                }
            }
            const double tGround = groundDistance(mS.ground, x, dir);
            const double tHit = freeFlight(density, x, dir, tGround, rng);
            if (std::isfinite(tHit)) {
                x += dir * tHit;
                inMedium = true;
            } else if (std::isfinite(tGround)) {
                x += dir * tGround;
                inMedium = false;
            } else {
                L += beta * skyRadiance(mS.sky, dir) * mS.sky.ambient;
                break;
            }
        }
        return L;
    }

    const RenderSettings& mS;
    const openvdb::FloatGrid& mGrid;
    RenderOccupancy mOcc;
    CameraRays mRays;
    PhaseFunction mPhase;
    RenderVec3 mSunDir;
    RenderVec3 mSunIrradiance;
    bool mSunOn = false;
    double mExtinction = 0.0;
};

}  // namespace

RenderedImage renderPathTraced(const openvdb::FloatGrid& grid, const RenderSettings& settings,
                               const std::function<bool()>& cancelled)
{
    const PathTracer tracer(grid, settings);
    RenderedImage img;
    img.width = settings.camera.width;
    img.height = settings.camera.height;
    const auto w = static_cast<std::size_t>(img.width);
    const std::size_t pixels = w * static_cast<std::size_t>(img.height);
    img.rgba.assign(pixels * 4, 0.0f);
    img.background.assign(pixels * 3, 0.0f);
    tbb::parallel_for(tbb::blocked_range<int>(0, img.height, 1),
                      [&](const tbb::blocked_range<int>& rows) {
                          TrilinearDensity density(grid, tracer.occupancy());
                          for (int py = rows.begin(); py != rows.end(); ++py) {
                              if (cancelled && cancelled()) return;
                              const std::size_t row = static_cast<std::size_t>(py) * w;
                              for (int px = 0; px < img.width; ++px)
                                  tracer.pixel(px, py, density, &img.rgba[(row + px) * 4],
                                               &img.background[(row + px) * 3]);
                          }
                      });
    return img;
}

}  // namespace cg::algo
