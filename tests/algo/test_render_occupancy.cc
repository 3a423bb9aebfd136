// RenderOccupancy's spans: every point where a trilinear sample is positive lies in a span,
// and blocks where no sample can be positive (the margin around a leaf) are left out.

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>
#include <openvdb/tools/Interpolation.h>

#include "algo/CounterRandom.h"
#include "algo/render/RenderOccupancy.h"

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

}  // namespace
}  // namespace cg
