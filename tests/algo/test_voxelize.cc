// Voxelizer physics: conservation against the kernel's closed-form integral, symmetry of one
// particle's footprint, grid identity, sparsity, and determinism across thread counts.

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <stdexcept>
#include <tuple>
#include <vector>

#include <openvdb/tools/Count.h>

#include "algo/volume/Voxelize.h"

namespace cg {

namespace {

/// `n` particles uniform in a ball of `radius` metres around `centre` (fixed seed).
std::vector<float> ball(std::size_t n, const openvdb::Vec3d& centre, double radius,
                        std::uint32_t seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<float> xyz;
    xyz.reserve(3 * n);
    while (xyz.size() < 3 * n) {
        const openvdb::Vec3d p(u(rng), u(rng), u(rng));
        if (p.lengthSqr() > 1.0) continue;
        for (int a = 0; a < 3; ++a) xyz.push_back(static_cast<float>(centre[a] + radius * p[a]));
    }
    return xyz;
}

double activeSum(const openvdb::FloatGrid& grid)
{
    double sum = 0.0;
    for (auto it = grid.tree().cbeginValueOn(); it; ++it) sum += *it;
    return sum;
}

/// Every active voxel of `a` is active in `b` with the bit-identical value, and the counts
/// match.
void expectIdentical(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b)
{
    ASSERT_EQ(a.activeVoxelCount(), b.activeVoxelCount());
    ASSERT_EQ(a.tree().leafCount(), b.tree().leafCount());
    auto acc = b.getConstAccessor();
    std::size_t mismatches = 0;
    for (auto it = a.tree().cbeginValueOn(); it; ++it) {
        float v = 0.0f;
        if (!acc.probeValue(it.getCoord(), v) || v != *it) ++mismatches;
    }
    EXPECT_EQ(mismatches, 0u);
}

algo::VoxelizeSettings unclamped(double voxel, double radius, double density)
{
    algo::VoxelizeSettings s;
    s.voxelSize = voxel;
    s.radius = radius;
    s.density = density;
    s.clamp = false;
    return s;
}

}  // namespace

TEST(Voxelize, KernelIntegralsAreTheClosedForms)
{
    const double pi = 3.14159265358979323846;
    EXPECT_DOUBLE_EQ(algo::kernelIntegral(algo::VoxelKernel::Smooth, 2.0), 64.0 * pi * 8.0 / 315.0);
    EXPECT_DOUBLE_EQ(algo::kernelIntegral(algo::VoxelKernel::Sphere, 2.0), 4.0 * pi * 8.0 / 3.0);
}

TEST(Voxelize, TotalDensityTimesVoxelVolumeIsTheParticlesContribution)
{
    // Unclamped, sum(value) * dx^3 approximates N * density * integral(w). The lattice sum of a
    // smooth (C^2) kernel 2.5 voxels wide is within ~1e-3 of the integral for one particle,
    // and the error averages out over random offsets.
    const double dx = 0.5, radius = 1.25, density = 0.3;
    const std::size_t n = 20000;
    const auto xyz = ball(n, {3.0, -7.0, 1000.0}, 20.0, 1);
    const auto grid = algo::voxelizeParticles(xyz.data(), n, unclamped(dx, radius, density));
    const double total = activeSum(*grid) * dx * dx * dx;
    const double expected =
        static_cast<double>(n) * density * algo::kernelIntegral(algo::VoxelKernel::Smooth, radius);
    EXPECT_NEAR(total / expected, 1.0, 2e-4) << total << " vs " << expected;
}

TEST(Voxelize, OneParticleConservesToTheLatticeSumTolerance)
{
    // A single particle at assorted offsets: the lattice sum stays within 0.3% of the integral
    // for R = 3 voxels (measured worst: 0.22% at a voxel centre; the error of this C^2 kernel
    // falls off fast with R / voxel size).
    const double dx = 1.0, radius = 3.0, density = 1.0;
    const double expected = density * algo::kernelIntegral(algo::VoxelKernel::Smooth, radius);
    for (const float off : {0.0f, 0.25f, 0.5f, 0.37f}) {
        const float p[3] = {off, 0.5f * off, -off};
        const auto grid = algo::voxelizeParticles(p, 1, unclamped(dx, radius, density));
        EXPECT_NEAR(activeSum(*grid) / expected, 1.0, 3e-3) << "offset " << off;
    }
}

TEST(Voxelize, SphereKernelConservesOnAverage)
{
    const double dx = 1.0, radius = 2.0, density = 0.01;
    const std::size_t n = 20000;
    const auto xyz = ball(n, {0.0, 0.0, 0.0}, 30.0, 2);
    auto s = unclamped(dx, radius, density);
    s.kernel = algo::VoxelKernel::Sphere;
    const auto grid = algo::voxelizeParticles(xyz.data(), n, s);
    const double expected =
        static_cast<double>(n) * density * algo::kernelIntegral(algo::VoxelKernel::Sphere, radius);
    // A hard edge: each particle's count of voxel centres varies, but its mean is the volume.
    EXPECT_NEAR(activeSum(*grid) / expected, 1.0, 5e-3);
}

TEST(Voxelize, OneParticleFootprintIsSymmetric)
{
    // At a voxel centre: mirror voxels in every axis and axis permutations are equal.
    {
        const float p[3] = {2.0f, -3.0f, 5.0f};  // voxel (4, -6, 10) at dx = 0.5
        const auto grid = algo::voxelizeParticles(p, 1, unclamped(0.5, 1.6, 0.7));
        auto acc = grid->getConstAccessor();
        const openvdb::Coord c(4, -6, 10);
        EXPECT_FLOAT_EQ(acc.getValue(c), 0.7f);
        int checked = 0;
        for (int i = -4; i <= 4; ++i)
            for (int j = -4; j <= 4; ++j)
                for (int k = -4; k <= 4; ++k) {
                    const float v = acc.getValue(c.offsetBy(i, j, k));
                    EXPECT_EQ(v, acc.getValue(c.offsetBy(-i, j, k)));
                    EXPECT_EQ(v, acc.getValue(c.offsetBy(i, -j, k)));
                    EXPECT_EQ(v, acc.getValue(c.offsetBy(i, j, -k)));
                    EXPECT_EQ(v, acc.getValue(c.offsetBy(j, k, i)));
                    EXPECT_EQ(v, acc.getValue(c.offsetBy(k, i, j)));
                    checked += v > 0.0f;
                }
        // R = 3.2 voxels: the voxel centres strictly inside the ball.
        int inside = 0;
        for (int i = -4; i <= 4; ++i)
            for (int j = -4; j <= 4; ++j)
                for (int k = -4; k <= 4; ++k) inside += i * i + j * j + k * k < 3.2 * 3.2;
        EXPECT_EQ(checked, inside);
        EXPECT_EQ(grid->activeVoxelCount(), static_cast<openvdb::Index64>(inside));
    }
    // At a voxel corner: voxel i mirrors to 1 - i (and -1 - i at negative corners).
    {
        const float p[3] = {0.25f, 0.25f, -0.25f};  // corner (0.5, 0.5, -0.5) in voxels
        const auto grid = algo::voxelizeParticles(p, 1, unclamped(0.5, 1.0, 1.0));
        auto acc = grid->getConstAccessor();
        for (int i = -3; i <= 3; ++i)
            for (int j = -3; j <= 3; ++j)
                for (int k = -3; k <= 3; ++k) {
                    const float v = acc.getValue({i, j, k});
                    EXPECT_EQ(v, acc.getValue({1 - i, j, k}));
                    EXPECT_EQ(v, acc.getValue({i, 1 - j, k}));
                    EXPECT_EQ(v, acc.getValue({i, j, -1 - k}));
                }
        EXPECT_GT(acc.getValue({0, 0, -1}), 0.0f);
    }
}

TEST(Voxelize, GridIsADensityFogVolumeWithTheVoxelSize)
{
    const auto xyz = ball(5000, {100.0, 50.0, 1500.0}, 15.0, 3);
    algo::VoxelizeSettings s;
    s.voxelSize = 0.75;
    s.radius = 2.0;
    s.density = 0.5;
    const auto grid = algo::voxelizeParticles(xyz.data(), 5000, s);
    EXPECT_EQ(grid->getName(), "density");
    EXPECT_EQ(grid->getGridClass(), openvdb::GRID_FOG_VOLUME);
    EXPECT_TRUE(grid->transform().isLinear());
    EXPECT_EQ(grid->voxelSize(), openvdb::Vec3d(0.75));
    EXPECT_EQ(grid->indexToWorld(openvdb::Vec3d(4.0, -2.0, 1.0)), openvdb::Vec3d(3.0, -1.5, 0.75));
    EXPECT_EQ(grid->background(), 0.0f);
    // Clamped: values in (0, 1], and this dense ball saturates.
    const auto range = openvdb::tools::minMax(grid->tree());
    const float lo = range.min(), hi = range.max();
    EXPECT_GT(lo, 0.0f);
    EXPECT_EQ(hi, 1.0f);
    // The world-space bounding box of the active voxels is the ball, widened by R.
    const openvdb::CoordBBox box = grid->evalActiveVoxelBoundingBox();
    const openvdb::Vec3d lower = grid->indexToWorld(box.min());
    const openvdb::Vec3d upper = grid->indexToWorld(box.max());
    EXPECT_NEAR(lower.x(), 100.0 - 17.0, 1.0);
    EXPECT_NEAR(upper.z(), 1500.0 + 17.0, 1.0);
}

TEST(Voxelize, MatchesABruteForceSumInParticleOrder)
{
    const std::size_t n = 3000;
    const auto xyz = ball(n, {-40.0, 12.0, 7.0}, 6.0, 4);
    const auto s = unclamped(0.5, 1.1, 0.05);
    const auto grid = algo::voxelizeParticles(xyz.data(), n, s);
    // Reference: every particle against every voxel of its bounding box, in index order.
    std::map<std::tuple<int, int, int>, double> ref;
    const double rv = s.radius / s.voxelSize;
    for (std::size_t i = 0; i < n; ++i) {
        double q[3];
        for (int a = 0; a < 3; ++a) q[a] = xyz[3 * i + a] / s.voxelSize;
        for (int x = int(std::floor(q[0] - rv)); x <= int(std::ceil(q[0] + rv)); ++x)
            for (int y = int(std::floor(q[1] - rv)); y <= int(std::ceil(q[1] + rv)); ++y)
                for (int z = int(std::floor(q[2] - rv)); z <= int(std::ceil(q[2] + rv)); ++z) {
                    const double r2 =
                        (x - q[0]) * (x - q[0]) + (y - q[1]) * (y - q[1]) + (z - q[2]) * (z - q[2]);
                    if (r2 >= rv * rv) continue;
                    const double t = 1.0 - r2 / (rv * rv);
                    ref[{x, y, z}] += s.density * t * t * t;
                }
    }
    auto acc = grid->getConstAccessor();
    double worst = 0.0;
    std::size_t refActive = 0;
    for (const auto& [c, v] : ref) {
        const openvdb::Coord ijk(std::get<0>(c), std::get<1>(c), std::get<2>(c));
        worst = std::max(worst, std::fabs(acc.getValue(ijk) - v));
        refActive += v > 1e-9;
    }
    EXPECT_LT(worst, 1e-4);
    // Voxels at r ~ R get ~1e-20 in one precision and 0 in the other: compare loosely.
    EXPECT_NEAR(static_cast<double>(grid->activeVoxelCount()), static_cast<double>(refActive),
                0.001 * static_cast<double>(refActive));
}

TEST(Voxelize, IdenticalForOneAndTwoThreads)
{
    // Two overlapping clusters, many particles per voxel: summation order matters here.
    auto xyz = ball(300000, {0.0, 0.0, 500.0}, 40.0, 5);
    const auto more = ball(200000, {30.0, 10.0, 520.0}, 25.0, 6);
    xyz.insert(xyz.end(), more.begin(), more.end());
    const std::size_t n = xyz.size() / 3;
    for (const bool clamp : {false, true}) {
        algo::VoxelizeSettings s;
        s.voxelSize = 1.0;
        s.radius = 2.5;
        s.density = 0.02;
        s.clamp = clamp;
        openvdb::FloatGrid::Ptr one, two;
        {
            tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
            one = algo::voxelizeParticles(xyz.data(), n, s);
        }
        {
            tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
            two = algo::voxelizeParticles(xyz.data(), n, s);
        }
        expectIdentical(*one, *two);
        expectIdentical(*two, *one);
        EXPECT_GT(one->activeVoxelCount(), 100000u);
    }
}

TEST(Voxelize, MemoryFollowsOccupiedSpaceNotTheBoundingBox)
{
    // Two clusters 10 km apart, along x only (keys fit 32 bits) and along all three axes
    // (wide keys): the grid holds each cluster's voxels and nothing between.
    const auto s = unclamped(1.0, 2.0, 0.1);
    const auto a = ball(20000, {0.0, 0.0, 0.0}, 15.0, 7);
    const auto gridA = algo::voxelizeParticles(a.data(), 20000, s);
    for (const openvdb::Vec3d offset :
         {openvdb::Vec3d(10000.0, 0.0, 0.0), openvdb::Vec3d(10000.0, -9000.0, 8000.0)}) {
        const auto b = ball(20000, offset, 15.0, 8);
        const auto gridB = algo::voxelizeParticles(b.data(), 20000, s);
        std::vector<float> both(a);
        both.insert(both.end(), b.begin(), b.end());
        const auto grid = algo::voxelizeParticles(both.data(), 40000, s);

        EXPECT_EQ(grid->activeVoxelCount(), gridA->activeVoxelCount() + gridB->activeVoxelCount());
        EXPECT_EQ(grid->tree().leafCount(), gridA->tree().leafCount() + gridB->tree().leafCount());
        // Far apart, each voxel sums one cluster's particles in the same order: same bits.
        auto acc = grid->getConstAccessor();
        for (const auto* part : {gridA.get(), gridB.get()})
            for (auto it = part->tree().cbeginValueOn(); it; ++it)
                ASSERT_EQ(acc.getValue(it.getCoord()), *it);
        // Memory: two clusters' leaves plus a few internal nodes, not 10^12 voxels of air.
        const double clusterBytes = static_cast<double>(gridA->memUsage());
        EXPECT_LT(static_cast<double>(grid->memUsage()), 2.5 * clusterBytes);
        const openvdb::CoordBBox box = grid->evalActiveVoxelBoundingBox();
        EXPECT_GT(box.dim().x(), 9900);
        EXPECT_LT(static_cast<double>(grid->activeVoxelCount()),
                  0.01 * static_cast<double>(box.volume()));
    }
}

TEST(Voxelize, FilteringKeepsTopologyAndRange)
{
    const auto xyz = ball(20000, {0.0, 0.0, 0.0}, 10.0, 9);
    algo::VoxelizeSettings s;
    s.voxelSize = 0.5;
    s.radius = 1.0;
    s.density = 0.2;
    auto grid = algo::voxelizeParticles(xyz.data(), 20000, s);
    const auto before = grid->activeVoxelCount();
    const auto copy = grid->deepCopy();
    algo::filterVolume(*grid, algo::VoxelFilter::Gaussian, 1, 2);
    EXPECT_EQ(grid->activeVoxelCount(), before);
    const auto range = openvdb::tools::minMax(grid->tree());
    const float lo = range.min(), hi = range.max();
    EXPECT_GE(lo, 0.0f);
    EXPECT_LE(hi, 1.0f);
    // Something changed, and "none" changes nothing.
    EXPECT_NE(activeSum(*grid), activeSum(*copy));
    auto untouched = copy->deepCopy();
    algo::filterVolume(*untouched, algo::VoxelFilter::None, 1, 1);
    EXPECT_EQ(activeSum(*untouched), activeSum(*copy));
}

TEST(Voxelize, EmptyInputGivesAnEmptyGrid)
{
    const auto grid = algo::voxelizeParticles(nullptr, 0, algo::VoxelizeSettings{});
    EXPECT_EQ(grid->activeVoxelCount(), 0u);
    EXPECT_EQ(grid->getName(), "density");
}

TEST(Voxelize, RefusesBadInput)
{
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float bad[3] = {0.0f, nan, 0.0f};
    EXPECT_THROW(algo::voxelizeParticles(bad, 1, algo::VoxelizeSettings{}), std::invalid_argument);
    const float far[3] = {0.0f, 0.0f, 1e9f};
    EXPECT_THROW(algo::voxelizeParticles(far, 1, algo::VoxelizeSettings{}), std::invalid_argument);
    algo::VoxelizeSettings s;
    s.voxelSize = 0.0;
    const float ok[3] = {0.0f, 0.0f, 0.0f};
    EXPECT_THROW(algo::voxelizeParticles(ok, 1, s), std::invalid_argument);
    s.voxelSize = 1.0;
    s.radius = 40.0;
    EXPECT_THROW(algo::voxelizeParticles(ok, 1, s), std::invalid_argument);
    EXPECT_THROW(algo::voxelKernelFromName("cubic"), std::invalid_argument);
    EXPECT_THROW(algo::voxelFilterFromName("box"), std::invalid_argument);
}

}  // namespace cg

namespace cg {

namespace {

/// `count` particles spread uniformly over a cube of `size` metres (a cloud's spacing).
std::vector<float> spreadParticles(std::size_t count, float size)
{
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, size);
    std::vector<float> xyz(3 * count);
    for (float& v : xyz) v = u(rng);
    return xyz;
}

}  // namespace

TEST(VoxelizeGuard, AbsurdlySmallVoxelsAreRefusedBeforeAnyWork)
{
    // The audit's case: 4,382 cloud particles over kilometres, 1 cm voxels, a 32-voxel radius
    // (4.8 GB and a 2.4 GB VDB when it was let through).
    const std::vector<float> xyz = spreadParticles(4382, 4000.0f);
    algo::VoxelizeSettings s;
    s.voxelSize = 0.01;
    s.radius = 0.32;
    s.maxBytes = 4ull << 30;
    EXPECT_THROW(algo::voxelizeParticles(xyz.data(), 4382, s), algo::VoxelizeTooLarge);
    // The same particles at a cloud's resolution pass.
    s.voxelSize = 40.0;
    s.radius = 160.0;
    EXPECT_NO_THROW(algo::voxelizeParticles(xyz.data(), 4382, s));
}

TEST(VoxelizeGuard, TheMemoryBoundIsAnUpperBoundOfTheGrid)
{
    for (const double radius : {1.0, 4.0, 12.0}) {
        const std::vector<float> xyz = spreadParticles(3000, 200.0f);
        algo::VoxelizeSettings s;
        s.voxelSize = 1.0;
        s.radius = radius;
        const auto grid = algo::voxelizeParticles(xyz.data(), 3000, s);
        const double extent[3] = {200.0, 200.0, 200.0};
        EXPECT_GE(algo::voxelizeMemoryBound(3000, extent, radius), grid->memUsage())
            << "radius " << radius;
    }
    const double huge[3] = {2e6, 2e6, 2e6};
    EXPECT_GT(algo::voxelizeMemoryBound(std::size_t(1) << 40, huge, 32.0), std::uint64_t{1} << 50);
}

}  // namespace cg
