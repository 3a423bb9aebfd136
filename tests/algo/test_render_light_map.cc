// RenderLightMap: τ toward a distant light from a sparse lattice, against closed forms and a
// brute-force march.

#include <cmath>

#include <gtest/gtest.h>
#include <openvdb/tools/Interpolation.h>

#include "algo/render/lighting/RenderLightMap.h"
#include "algo/render/media/RenderOccupancy.h"
#include "support/RenderTestVolumes.h"

namespace cg {
namespace {

using algo::RenderVec3;

constexpr double kVoxel = 10.0, kExtinction = 0.01;

/// Two 8-voxel cubes at opposite corners of a 128-voxel box: a sparse field whose dense
/// light lattice (about 2.2 million texels) would not fit the budget at one voxel a texel.
openvdb::FloatGrid::Ptr twoCubes()
{
    auto grid = test::makeBox(kVoxel, openvdb::Coord(0), openvdb::Coord(7), 1.0f);
    grid->tree().fill(openvdb::CoordBBox(openvdb::Coord(120), openvdb::Coord(127)), 1.0f, true);
    return grid;
}

/// τ from p toward the light by marching the trilinear density in small steps.
double marched(const openvdb::FloatGrid& grid, const RenderVec3& p, const RenderVec3& light)
{
    auto acc = grid.getConstAccessor();
    const RenderVec3 w = light.unitSafe();
    const double ds = 0.05 * kVoxel;
    double tau = 0.0;
    for (double s = 0.5 * ds; s < 3000.0; s += ds)
        tau += kExtinction * ds *
               openvdb::tools::BoxSampler::sample(acc, grid.transform().worldToIndex(p + w * s));
    return tau;
}

TEST(RenderLightMap, SparseColumnsKeepTexelsAsFineAsVoxels)
{
    const auto grid = twoCubes();
    const algo::RenderOccupancy occupancy(grid->tree());
    const std::size_t budget = std::size_t(1) << 20;  // under half the dense lattice
    const algo::RenderLightMap map(*grid, occupancy, RenderVec3(0, 0, 1), kExtinction, 1.0, 0.5,
                                   budget);
    EXPECT_DOUBLE_EQ(map.texel(), kVoxel);
    EXPECT_LT(map.storedTexels(), std::size_t(20000));

    // A cube integrates to 8 voxels along an axis (makeBox): τ = σ 8 h below it, 0 above it
    // and in the clear air between the two.
    const double cube = kExtinction * 8 * kVoxel;
    EXPECT_NEAR(map.opticalDepth(RenderVec3(35, 35, -50)), cube, 1e-3 * cube);
    EXPECT_NEAR(map.opticalDepth(RenderVec3(1235, 1235, 500)), cube, 1e-3 * cube);
    EXPECT_NEAR(map.columnDepth(RenderVec3(1235, 1235, 1500)), cube, 1e-3 * cube);
    EXPECT_EQ(map.opticalDepth(RenderVec3(35, 35, 200)), 0.0);
    EXPECT_EQ(map.opticalDepth(RenderVec3(600, 600, 600)), 0.0);
    EXPECT_EQ(map.opticalDepth(RenderVec3(1235, 1235, 1400)), 0.0);
    // Halfway through the lower cube, half its depth.
    EXPECT_NEAR(map.opticalDepth(RenderVec3(35, 35, 35)), 0.5 * cube, 0.02 * cube);
}

TEST(RenderLightMap, SlantedLightAgreesWithAMarch)
{
    const auto grid = twoCubes();
    const algo::RenderOccupancy occupancy(grid->tree());
    const RenderVec3 light(0.4, -0.3, 0.8);
    const algo::RenderLightMap map(*grid, occupancy, light, kExtinction, 1.0, 0.25);
    // Points in and under each cube, where the column is smooth across a texel.
    for (const RenderVec3 p : {RenderVec3(35, 35, 20), RenderVec3(30, 45, -40),
                               RenderVec3(1230, 1240, 1215), RenderVec3(1220, 1250, 1150)}) {
        const double expected = marched(*grid, p, light);
        ASSERT_GT(expected, 0.05);
        EXPECT_NEAR(map.opticalDepth(p), expected, 0.03 * expected) << p;
    }
}

}  // namespace
}  // namespace cg
