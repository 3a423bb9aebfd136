// RenderOccupancy's spans: every point where a trilinear sample is positive lies in a span,
// and blocks where no sample can be positive (the margin around a leaf) are left out.

#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <openvdb/tools/Interpolation.h>

#include "algo/CounterRandom.h"
#include "algo/render/integrators/RenderPathTrace.h"
#include "algo/render/integrators/RenderVolume.h"
#include "algo/render/media/RenderOccupancy.h"

namespace cg {
namespace {

using Span = algo::RenderOccupancy::Span;

/// Scattered single voxels and small clumps in a few leaves: most blocks of the one-voxel
/// margin around the leaves hold no positive sample.
openvdb::FloatGrid::Ptr sparseGrid()
{
    auto grid = openvdb::FloatGrid::create(0.0f);
    auto acc = grid->getAccessor();
    for (std::uint64_t n = 0; n < 60; ++n) {
        const openvdb::Coord c(static_cast<int>(64.0 * algo::counterUniform(3, n, 0)) - 32,
                               static_cast<int>(64.0 * algo::counterUniform(3, n, 1)) - 32,
                               static_cast<int>(64.0 * algo::counterUniform(3, n, 2)) - 32);
        acc.setValue(c, 0.5f);
        if (n % 3 == 0) acc.setValue(c.offsetBy(1, 0, 0), 0.25f);
    }
    acc.setValue(openvdb::Coord(5, 5, 5), -0.5f);  // active, never positive
    return grid;
}

bool inside(const std::vector<Span>& spans, double t)
{
    for (const Span& s : spans)
        if (t >= s.t0 && t <= s.t1) return true;
    return false;
}

TEST(RenderOccupancy, EveryPositiveSampleOfARayLiesInItsSpans)
{
    const openvdb::FloatGrid::Ptr grid = sparseGrid();
    const algo::RenderOccupancy occupancy(grid->tree());
    auto acc = grid->getConstAccessor();
    std::vector<Span> spans;
    std::uint64_t positives = 0;
    for (std::uint64_t r = 0; r < 3000; ++r) {
        // Rays from a sphere around the voxels toward points among them.
        const openvdb::Vec3d from(algo::counterUniform(4, r, 0) - 0.5,
                                  algo::counterUniform(4, r, 1) - 0.5,
                                  algo::counterUniform(4, r, 2) - 0.5);
        const openvdb::Vec3d origin = from.unitSafe() * 80.0;
        const openvdb::Coord aim(static_cast<int>(64.0 * algo::counterUniform(3, r % 60, 0)) - 32,
                                 static_cast<int>(64.0 * algo::counterUniform(3, r % 60, 1)) - 32,
                                 static_cast<int>(64.0 * algo::counterUniform(3, r % 60, 2)) - 32);
        const openvdb::Vec3d jitter(algo::counterUniform(5, r, 0), algo::counterUniform(5, r, 1),
                                    algo::counterUniform(5, r, 2));
        const openvdb::Vec3d dir = aim.asVec3d() + jitter - origin;
        spans.clear();
        occupancy.spans(origin, dir, 0.0, 2.0, spans);
        for (double t = 0.0; t < 2.0; t += 1.0 / 4096.0) {
            if (!(openvdb::tools::BoxSampler::sample(acc, origin + dir * t) > 0.0f)) continue;
            ++positives;
            ASSERT_TRUE(inside(spans, t)) << "ray " << r << " at t = " << t;
        }
    }
    EXPECT_GT(positives, 10000u);
}

TEST(RenderOccupancy, BlocksWhereNoSampleCanBePositiveAreLeftOut)
{
    // One positive voxel in the middle of its leaf: the blocks around the leaf are within one
    // voxel of it, but no sample in them reads it.
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->tree().setValue(openvdb::Coord(4, 4, 4), 1.0f);
    const algo::RenderOccupancy occupancy(grid->tree());
    std::vector<Span> spans;
    // Through the leaf's neighbour above (z in 8..15), along x.
    occupancy.spans(openvdb::Vec3d(-20.0, 4.5, 12.5), openvdb::Vec3d(1.0, 0.0, 0.0), 0.0, 40.0,
                    spans);
    EXPECT_TRUE(spans.empty());
    // Through the voxel itself: one span that holds it.
    occupancy.spans(openvdb::Vec3d(-20.0, 4.5, 4.5), openvdb::Vec3d(1.0, 0.0, 0.0), 0.0, 40.0,
                    spans);
    ASSERT_FALSE(spans.empty());
    EXPECT_TRUE(inside(spans, 24.5));
}

/// Two active voxels, at the origin and at `far`.
openvdb::FloatGrid::Ptr twoVoxels(const openvdb::Coord& far)
{
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->tree().setValue(openvdb::Coord(0, 0, 0), 0.5f);
    grid->tree().setValue(far, 0.5f);
    return grid;
}

TEST(RenderOccupancy, ADomainWhoseBlockCountWrapsIsRefusedWithItsExtents)
{
    // The domain runs from the block below the first leaf to the one above the last: with the
    // far voxel's leaf 2^22 - 3 blocks out (2^21 - 3 on y and z) that is 2^22 x 2^21 x 2^21
    // blocks, 2^64, whose 64-bit product is 0.
    const openvdb::Coord far((1 << 25) - 24, (1 << 24) - 24, (1 << 24) - 24);
    const openvdb::FloatGrid::Ptr grid = twoVoxels(far);
    const std::string extents = "4194304 x 2097152 x 2097152 blocks";
    for (const bool majorants : {false, true}) {
        try {
            const algo::RenderOccupancy occupancy(grid->tree(), majorants);
            ADD_FAILURE() << "a domain of 2^64 blocks was accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(extents), std::string::npos) << e.what();
        }
    }
    // The box a VDB file records gives the same answer before the voxels are read.
    const std::string problem =
        algo::RenderOccupancy::domainProblem(grid->evalActiveVoxelBoundingBox());
    EXPECT_NE(problem.find(extents), std::string::npos) << problem;
    // Both renderers refuse it as bad input.
    algo::RenderSettings settings;
    settings.camera.width = 8;
    settings.camera.height = 6;
    EXPECT_THROW(algo::renderFogVolume(*grid, settings), std::invalid_argument);
    EXPECT_THROW(algo::renderPathTraced(*grid, settings, {}), std::invalid_argument);
}

TEST(RenderOccupancy, VoxelsAtTheEndsOfTheIndexRangeAreRefusedWithoutOverflow)
{
    // The sampling margin takes these one voxel past the int range on each side.
    constexpr int kMin = std::numeric_limits<int>::min(), kMax = std::numeric_limits<int>::max();
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->tree().setValue(openvdb::Coord(kMin, kMin, 0), 0.5f);
    grid->tree().setValue(openvdb::Coord(kMax, kMax, 0), 0.5f);
    const std::string extents = "536870914 x 536870914 x 3 blocks";
    try {
        const algo::RenderOccupancy occupancy(grid->tree());
        ADD_FAILURE() << "a domain of 2^58 blocks was accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find(extents), std::string::npos) << e.what();
    }
    EXPECT_NE(
        algo::RenderOccupancy::domainProblem(grid->evalActiveVoxelBoundingBox()).find(extents),
        std::string::npos);
}

TEST(RenderOccupancy, TheRecordedBoxPredictsTheDomainOfAVolumeThatFits)
{
    // Unaligned boxes, negative coordinates, a tile: the box-based answer agrees with the
    // constructor's on both sides of the limit.
    for (const int far : {4000, -4000, 40000, -70000}) {
        auto grid = twoVoxels(openvdb::Coord(far, 3 * far / 4 + 5, 1000 + 3));
        grid->tree().addTile(1, openvdb::Coord(128, 128, 128), 0.25f, true);
        const std::string problem =
            algo::RenderOccupancy::domainProblem(grid->evalActiveVoxelBoundingBox());
        bool refused = false;
        try {
            const algo::RenderOccupancy occupancy(grid->tree());
        } catch (const std::invalid_argument& e) {
            refused = true;
            EXPECT_EQ(problem, e.what());
        }
        EXPECT_EQ(refused, !problem.empty()) << far;
    }
}

}  // namespace
}  // namespace cg
