// TrilinearDensity: the ray marches' density lookup equals OpenVDB's BoxSampler bit for bit.

#include <cstdint>

#include <gtest/gtest.h>
#include <openvdb/tools/Interpolation.h>

#include "algo/CounterRandom.h"
#include "algo/render/media/TrilinearDensity.h"
#include "support/RenderTestVolumes.h"

namespace cg {
namespace {

/// A ball of varying density (voxels, in leaves) over a constant box stored as tiles, so that
/// lookups meet leaves, tiles, the background and the seams between them.
openvdb::FloatGrid::Ptr mixedGrid()
{
    auto grid = test::makeBox(10.0, openvdb::Coord(16), openvdb::Coord(47), 0.5f);
    auto acc = grid->getAccessor();
    for (int i = -20; i <= 20; ++i)
        for (int j = -20; j <= 20; ++j)
            for (int k = -20; k <= 20; ++k)
                if (i * i + j * j + k * k <= 400 && ((i ^ j ^ k) & 3) != 0)  // holes
                    acc.setValue(openvdb::Coord(i, j, k),
                                 0.01f * static_cast<float>((i * 7 + j * 13 + k * 29) & 63) -
                                     0.05f);  // some negative
    return grid;
}

/// What the renderers use of a sample: its positive part.
float positive(float density) { return density > 0.0f ? density : 0.0f; }

TEST(TrilinearDensity, EqualsBoxSamplerBitForBitWhereItIsPositive)
{
    const openvdb::FloatGrid::Ptr grid = mixedGrid();
    ASSERT_GT(grid->tree().activeTileCount(), 0u);  // the box is held as tiles
    const algo::RenderOccupancy occupancy(grid->tree());
    algo::TrilinearDensity density(*grid, occupancy);
    auto acc = grid->getConstAccessor();
    std::uint64_t zero = 0;
    // Random points, then a march through them in small steps (the way rays use it).
    for (std::uint64_t n = 0; n < 200000; ++n) {
        const openvdb::Vec3d p(-30.0 + 90.0 * algo::counterUniform(1, n, 0),
                               -30.0 + 90.0 * algo::counterUniform(1, n, 1),
                               -30.0 + 90.0 * algo::counterUniform(1, n, 2));
        const float expected = openvdb::tools::BoxSampler::sample(acc, p);
        ASSERT_EQ(positive(density.sample(p)), positive(expected)) << p;
        if (!(expected > 0.0f)) ++zero;
    }
    EXPECT_GT(zero, 10000u);  // the points also fall where the occupancy skips the grid
    const openvdb::Vec3d d = openvdb::Vec3d(1.0, 0.7, 0.3).unit();
    for (double t = 0.0; t < 120.0; t += 0.37) {
        const openvdb::Vec3d p = openvdb::Vec3d(-25.0, -20.0, -8.0) + d * t;
        ASSERT_EQ(positive(density.sample(p)), positive(openvdb::tools::BoxSampler::sample(acc, p)))
            << p;
    }
}

}  // namespace
}  // namespace cg
