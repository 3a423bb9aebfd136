// The cloud-shape measures (algo/volume/CloudMetrics.h) on volumes whose answers are known in
// closed form.

#include <gtest/gtest.h>

#include <cmath>

#include "algo/volume/CloudMetrics.h"

namespace cg::algo {

namespace {

openvdb::FloatGrid::Ptr emptyGrid(double voxel)
{
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel));
    return grid;
}

}  // namespace

TEST(CloudMetrics, AHomogeneousSlabHasATopEdgeOfOnePointNineMeanFreePathsAndAFlatBase)
{
    // 10 m voxels, value 1, extinction 0.01 /m: tau 0.1 a voxel, so from above tau 0.1 is
    // reached after 10 m and tau 2 after 200 m: 190 m.
    auto grid = emptyGrid(10.0);
    grid->denseFill(openvdb::CoordBBox(openvdb::Coord(0, 0, 100), openvdb::Coord(39, 39, 159)),
                    1.0f, true);
    CloudMetricsOptions options;
    options.extinction = 0.01;
    const CloudMetrics m = measureCloud(*grid, options);
    EXPECT_EQ(m.thickColumns, 40u * 40u);
    EXPECT_NEAR(m.topEdgeMedian, 190.0, 1e-6);
    EXPECT_NEAR(m.topEdgeP90, 190.0, 1e-6);
    // The slab spans z 995 to 1595 m: tau 0.5 from below at 1045 m, from above at 1545 m.
    EXPECT_NEAR(m.baseP10, 1045.0, 1e-6);
    EXPECT_NEAR(m.baseP90, 1045.0, 1e-6);
    EXPECT_NEAR(m.top, 1545.0, 1e-6);
    EXPECT_EQ(m.baseSpread, 0.0);
    // A box's outline is straight: dimension 1.
    EXPECT_NEAR(m.sideOutlineDimension, 1.0, 0.05);  // its corners, over 3 scales
}

TEST(CloudMetrics, DiscsOfManySizesSeenFromAboveHaveAnAreaPerimeterDimensionNearOne)
{
    // Cylinders of radii 3 to 40 voxels: perimeter ~ area^(1/2), so D = 2 x 1/2 = 1.
    auto grid = emptyGrid(10.0);
    auto acc = grid->getAccessor();
    int cx = 50;
    for (const int r : {3, 5, 8, 12, 18, 27, 40}) {
        for (int x = -r; x <= r; ++x)
            for (int y = -r; y <= r; ++y)
                if (x * x + y * y <= r * r)
                    for (int z = 0; z < 10; ++z) acc.setValue(openvdb::Coord(cx + x, y, z), 1.0f);
        cx += 2 * 40 + 10;  // apart by more than the largest diameter
    }
    CloudMetricsOptions options;
    options.extinction = 0.1;
    const CloudMetrics m = measureCloud(*grid, options);
    EXPECT_EQ(m.clouds, 7u);
    // Pixel outlines of discs measure their L1 length, 4/pi of the circle's, at every size:
    // the slope, hence D, is unchanged.
    EXPECT_NEAR(m.areaPerimeterDimension, 1.0, 0.05);
}

TEST(CloudMetrics, ACloudBaseTiltedByItsOwnDepthSpreadsOverItsTenToNinetyPercentRange)
{
    // A slab whose base rises with x from 1000 m over 0..390 m across: base heights spread
    // uniformly over 400 m (one step a column of voxels), tops at one height.
    auto grid = emptyGrid(10.0);
    auto acc = grid->getAccessor();
    for (int x = 0; x < 40; ++x)
        for (int y = 0; y < 10; ++y)
            for (int z = 100 + x; z < 300; ++z) acc.setValue(openvdb::Coord(x, y, z), 1.0f);
    CloudMetricsOptions options;
    options.extinction = 1.0;  // tau 10 a voxel: the base is where the voxels start
    const CloudMetrics m = measureCloud(*grid, options);
    EXPECT_NEAR(m.baseP90 - m.baseP10, 320.0, 10.0 + 1e-6);
    EXPECT_NEAR(m.baseSpread, (m.baseP90 - m.baseP10) / (m.top - m.baseMedian), 1e-12);
}

TEST(CloudMetrics, AnEmptyGridMeasuresNothing)
{
    const CloudMetrics m = measureCloud(*emptyGrid(10.0), {});
    EXPECT_TRUE(std::isnan(m.sideOutlineDimension));
    EXPECT_TRUE(std::isnan(m.topEdgeMedian));
    EXPECT_EQ(m.clouds, 0u);
}

}  // namespace cg::algo
