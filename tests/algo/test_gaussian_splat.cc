// The Gaussian splat (trilinear deposit + separable blur): the smooth kernel's integral and
// peak, the particle's centroid kept, the kernel's second moment, the same bits for any
// thread count and any order of the particles, and its refusals.

#include <gtest/gtest.h>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "algo/volume/GaussianSplat.h"
#include "algo/volume/Voxelize.h"
#include "support/GridChecksum.h"

namespace cg {

namespace {

algo::VoxelizeSettings gaussian(double voxel, double radius, double density)
{
    algo::VoxelizeSettings s;
    s.voxelSize = voxel;
    s.radius = radius;
    s.density = density;
    s.clamp = false;
    s.kernel = algo::VoxelKernel::Gaussian;
    return s;
}

/// Sum, centroid and variance per axis (index space, voxels) of a grid's active values.
struct Moments {
    double sum = 0.0;
    double mean[3] = {0.0, 0.0, 0.0};
    double variance[3] = {0.0, 0.0, 0.0};
    float peak = 0.0f;
};

Moments moments(const openvdb::FloatGrid& grid)
{
    Moments m;
    for (auto it = grid.tree().cbeginValueOn(); it; ++it) {
        m.sum += *it;
        m.peak = std::max(m.peak, *it);
        for (int a = 0; a < 3; ++a) m.mean[a] += *it * it.getCoord()[a];
    }
    for (double& c : m.mean) c /= m.sum;
    for (auto it = grid.tree().cbeginValueOn(); it; ++it)
        for (int a = 0; a < 3; ++a) {
            const double d = it.getCoord()[a] - m.mean[a];
            m.variance[a] += *it * d * d;
        }
    for (double& v : m.variance) v /= m.sum;
    return m;
}

std::vector<float> scattered(std::size_t n, double extent, std::uint32_t seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-extent, extent);
    std::vector<float> xyz(3 * n);
    for (float& c : xyz) c = static_cast<float>(u(rng));
    return xyz;
}

}  // namespace

TEST(GaussianSplat, SigmaGivesTheSmoothKernelsIntegralAtTheSamePeak)
{
    const double pi = 3.14159265358979323846, r = 3.7;
    const double sigma = algo::gaussianKernelSigma(r);
    EXPECT_NEAR(std::pow(2.0 * pi, 1.5) * sigma * sigma * sigma,
                algo::kernelIntegral(algo::VoxelKernel::Smooth, r), 1e-9);
    EXPECT_NEAR(sigma / r, 0.3435, 1e-4);
    EXPECT_EQ(algo::kernelIntegral(algo::VoxelKernel::Gaussian, r),
              algo::kernelIntegral(algo::VoxelKernel::Smooth, r));
}

TEST(GaussianSplat, OneParticleKeepsItsMassAndCentroidAndTheKernelsWidth)
{
    // Unclamped: the deposit's weights sum to exactly 1 and the taps to 1, so the grid
    // holds the kernel's integral exactly; both are symmetric, so the centroid is the
    // particle. The variance per axis is the blur's plus the deposit's f (1 - f), f the
    // offset from the voxel below; averaged over f it is sigma^2 (taps cut at 3 sigma_b:
    // the taps reach past 3 sigma_b, so they keep about 99% of its variance).
    const double dx = 2.0, radius = 8.0, density = 0.5;  // 4 voxels
    const double sigma = algo::gaussianKernelSigma(radius / dx);
    const double mass = density * algo::kernelIntegral(algo::VoxelKernel::Smooth, radius / dx);
    double meanVariance = 0.0, meanPeak = 0.0;
    const float offsets[] = {0.0f, 0.125f, 0.25f, 0.375f, 0.5f, 0.625f, 0.75f, 0.875f};
    for (const float f : offsets) {
        const float p[3] = {static_cast<float>(dx * (10 + f)), static_cast<float>(dx * (-3 + f)),
                            static_cast<float>(dx * (400 + f))};
        const auto grid = algo::voxelizeParticles(p, 1, gaussian(dx, radius, density));
        const Moments m = moments(*grid);
        EXPECT_NEAR(m.sum / mass, 1.0, 1e-6) << f;
        EXPECT_NEAR(m.mean[0], 10 + f, 1e-4);
        EXPECT_NEAR(m.mean[1], -3 + f, 1e-4);
        EXPECT_NEAR(m.mean[2], 400 + f, 1e-4);
        EXPECT_NEAR(m.variance[0], m.variance[2], 1e-4);  // the same in every axis
        meanVariance += m.variance[0] / std::size(offsets);
        // The peak: higher than the kernel's (density) on a voxel centre, where the deposit
        // does not spread, lower between voxels; the kernel's on average.
        EXPECT_GT(m.peak, 0.75 * density);
        EXPECT_LT(m.peak, 1.2 * density);
        meanPeak += m.peak / std::size(offsets);
    }
    EXPECT_NEAR(meanVariance / (sigma * sigma), 0.99, 0.01);
    EXPECT_NEAR(meanPeak / density, 1.0, 0.05);
}

TEST(GaussianSplat, ANarrowKernelIsTheCloudInCellDepositWhereverTheParticleLies)
{
    // Under 1.2 voxels of radius nothing is left to blur: a particle's density is its mass
    // shared by the trilinear weights over its 8 voxels. The deposit is kept in blocks of 16
    // voxels a side, each with a layer of its neighbours' voxels: positions inside a block,
    // across each face, edge and corner, and on the negative side of the origin all give the
    // same 8 voxels.
    const auto s = gaussian(1.0, 1.0, 0.5);
    const double mass = s.density * algo::kernelIntegral(algo::VoxelKernel::Gaussian, 1.0);
    for (const float x : {7.25f, 15.25f, -0.75f, 31.5f})
        for (const float y : {3.5f, 15.75f, -16.25f})
            for (const float z : {15.5f, 9.75f, -1.25f}) {
                const float xyz[3] = {x, y, z};
                const auto grid = algo::voxelizeParticles(xyz, 1, s);
                ASSERT_EQ(grid->activeVoxelCount(), 8u) << x << " " << y << " " << z;
                const openvdb::Coord first(static_cast<int>(std::floor(x)),
                                           static_cast<int>(std::floor(y)),
                                           static_cast<int>(std::floor(z)));
                const double f[3] = {x - std::floor(x), y - std::floor(y), z - std::floor(z)};
                auto acc = grid->getConstAccessor();
                for (int corner = 0; corner < 8; ++corner) {
                    double w = 1.0;
                    openvdb::Coord c = first;
                    for (int a = 0; a < 3; ++a) {
                        const int step = (corner >> a) & 1;
                        c[a] += step;
                        w *= step ? f[a] : 1.0 - f[a];
                    }
                    EXPECT_NEAR(acc.getValue(c), mass * w, 1e-6 * mass) << c;
                }
            }
}

TEST(GaussianSplat, ManyParticlesConserveAndAgreeWithTheSmoothKernel)
{
    // A cloud of particles: same total as the smooth kernel (both carry its integral), and
    // the two fields differ by little where the splats overlap (about 40 particles a voxel).
    const std::size_t n = 200000;
    const auto xyz = scattered(n, 40.0, 3);
    auto s = gaussian(1.0, 3.0, 0.05);
    const auto g = algo::voxelizeParticles(xyz.data(), n, s);
    s.kernel = algo::VoxelKernel::Smooth;
    const auto smooth = algo::voxelizeParticles(xyz.data(), n, s);
    const Moments mg = moments(*g), ms = moments(*smooth);
    EXPECT_NEAR(mg.sum / ms.sum, 1.0, 2e-3);
    // Inside the cloud (|x| < 30), the mean relative difference of the densities.
    double diff = 0.0, total = 0.0;
    auto acc = smooth->getConstAccessor();
    for (auto it = g->tree().cbeginValueOn(); it; ++it) {
        const openvdb::Coord c = it.getCoord();
        if (std::abs(c.x()) > 30 || std::abs(c.y()) > 30 || std::abs(c.z()) > 30) continue;
        diff += std::abs(*it - acc.getValue(c));
        total += acc.getValue(c);
    }
    EXPECT_LT(diff / total, 0.05);
}

TEST(GaussianSplat, SameBitsForAnyThreadCountAndAnyOrder)
{
    const std::size_t n = 200000;
    const auto xyz = scattered(n, 300.0, 4);
    const auto s = gaussian(2.0, 7.0, 0.1);
    std::uint64_t bits[2];
    for (const int threads : {1, 2}) {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, threads);
        bits[threads - 1] = test::gridChecksum(*algo::voxelizeParticles(xyz.data(), n, s));
    }
    EXPECT_EQ(bits[0], bits[1]);
    // Added in reversed chunks of odd sizes, from parallel tasks: still the same bits.
    algo::GaussianSplatter splatter(s);
    const std::size_t chunk = 7919;
    const std::size_t chunks = (n + chunk - 1) / chunk;
    tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t i) {
        const std::size_t c = chunks - 1 - i;
        splatter.add(xyz.data() + 3 * c * chunk, std::min(chunk, n - c * chunk));
    });
    EXPECT_EQ(splatter.count(), n);
    EXPECT_EQ(test::gridChecksum(*splatter.finish()), bits[0]);
}

TEST(GaussianSplat, ClampsAndSwitchesOnOnlyWhatHoldsDensity)
{
    const std::size_t n = 50000;
    const auto xyz = scattered(n, 20.0, 5);
    auto s = gaussian(1.0, 2.0, 0.5);
    s.clamp = true;
    const auto grid = algo::voxelizeParticles(xyz.data(), n, s);
    float lo = 1.0f, hi = 0.0f;
    for (auto it = grid->tree().cbeginValueOn(); it; ++it) {
        lo = std::min(lo, *it);
        hi = std::max(hi, *it);
    }
    EXPECT_GT(lo, 0.0f);
    EXPECT_EQ(hi, 1.0f);
    EXPECT_EQ(grid->getGridClass(), openvdb::GRID_FOG_VOLUME);
    EXPECT_EQ(grid->getName(), "density");
    EXPECT_EQ(algo::voxelizeParticles(xyz.data(), 0, s)->activeVoxelCount(), 0u);
}

TEST(GaussianSplat, RefusesBadPositionsAndAnOverBudgetDeposit)
{
    auto s = gaussian(1.0, 2.0, 0.5);
    const float nan[3] = {0.0f, std::numeric_limits<float>::quiet_NaN(), 0.0f};
    EXPECT_THROW(algo::voxelizeParticles(nan, 1, s), std::invalid_argument);
    const float far[3] = {0.0f, 0.0f, 2.0e6f};
    EXPECT_THROW(algo::voxelizeParticles(far, 1, s), std::invalid_argument);
    // Particles 100 voxels apart each need their own deposit blocks (38 KiB): 1000 of them
    // pass a 1 MiB budget.
    std::vector<float> apart;
    for (int i = 0; i < 1000; ++i) apart.insert(apart.end(), {100.0f * i, 0.0f, 0.0f});
    s.maxBytes = std::uint64_t(1) << 20;
    EXPECT_THROW(algo::voxelizeParticles(apart.data(), 1000, s), algo::VoxelizeTooLarge);
    s.radius = 0.0;
    EXPECT_THROW(algo::GaussianSplatter{s}, std::invalid_argument);
}

}  // namespace cg
