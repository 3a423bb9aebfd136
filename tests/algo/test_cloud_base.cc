// Flat bases at the condensation level and values from the cloud's water
// (algo/volume/CloudBase.h).

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "algo/volume/CloudBase.h"

namespace cg::algo {

namespace {

/// A block of voxels of value v over x, y in [0, n) and z in [z0, z1], voxels of `voxel` m.
openvdb::FloatGrid::Ptr block(int n, int z0, int z1, float v, double voxel)
{
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel));
    grid->denseFill(openvdb::CoordBBox(openvdb::Coord(0, 0, z0), openvdb::Coord(n - 1, n - 1, z1)),
                    v, true);
    return grid;
}

/// Condensation points: the west half (x < 200 m) condensed at 1000 m, the east at 1100 m,
/// ten points a 100 m cell, in cells covering [0, 400) x [0, 400).
struct TwoLevels {
    std::vector<float> x, y, z;
    TwoLevels()
    {
        for (int cx = 0; cx < 4; ++cx)
            for (int cy = 0; cy < 4; ++cy)
                for (int k = 0; k < 10; ++k) {
                    x.push_back(100.0f * cx + 5.0f + 9.0f * k);
                    y.push_back(100.0f * cy + 50.0f);
                    z.push_back((cx < 2 ? 1000.0f : 1100.0f) + 2.0f * k);
                }
    }
};

}  // namespace

TEST(CloudBase, EachCellHoldsTheTenthPercentileOfItsCondensationHeights)
{
    const TwoLevels p;
    const CloudBaseField base(p.x.data(), p.y.data(), p.z.data(), p.x.size(), 100.0);
    // Ten heights h0 + 2k: the 10th percentile is the second, h0 + 2.
    EXPECT_DOUBLE_EQ(base.at(50.0, 50.0), 1002.0);
    EXPECT_DOUBLE_EQ(base.at(350.0, 350.0), 1102.0);
    // Bilinear between cell centres: halfway between the halves, halfway between heights.
    EXPECT_DOUBLE_EQ(base.at(200.0, 150.0), 1052.0);
    // Outside the cells: the 10th percentile of all.
    EXPECT_DOUBLE_EQ(base.overall(), 1004.0);
    EXPECT_DOUBLE_EQ(base.at(-5000.0, 9000.0), 1004.0);
}

TEST(CloudBase, NoColumnHoldsDensityBelowItsCondensationLevel)
{
    const TwoLevels p;
    const CloudBaseField base(p.x.data(), p.y.data(), p.z.data(), p.x.size(), 100.0);
    const double voxel = 10.0;
    auto grid = block(40, 80, 140, 1.0f, voxel);  // 800 to 1400 m
    CloudWaterSettings s;
    s.transition = 20.0;
    shapeCloudWater(*grid, base, s);
    std::size_t above = 0;
    for (auto v = grid->cbeginValueOn(); v; ++v) {
        const openvdb::Vec3d w = grid->indexToWorld(v.getCoord());
        const double h = w.z() - base.at(w.x(), w.y());
        ASSERT_GT(h, 0.0) << v.getCoord();
        // The smoothstep: full density from the transition up.
        if (h >= s.transition) {
            EXPECT_EQ(*v, 1.0f);
            ++above;
        } else {
            EXPECT_LT(*v, 1.0f);
        }
    }
    EXPECT_GT(above, 40u * 40u * 20u);
}

TEST(CloudBase, WaterValuesAreTheAdiabaticShareToTheTwoThirds)
{
    const TwoLevels p;
    const CloudBaseField base(p.x.data(), p.y.data(), p.z.data(), p.x.size(), 100.0);
    const AdiabaticWater water(16.0, 880.0);
    auto grid = block(40, 80, 300, 0.5f, 10.0);
    CloudWaterSettings s;
    s.water = &water;
    s.adiabaticFraction = 0.6;
    shapeCloudWater(*grid, base, s);
    auto acc = grid->getConstAccessor();
    for (const openvdb::Coord c :
         {openvdb::Coord(5, 5, 150), openvdb::Coord(35, 20, 250), openvdb::Coord(10, 30, 104)}) {
        const openvdb::Vec3d w = grid->indexToWorld(c);
        const double h = w.z() - base.at(w.x(), w.y());
        ASSERT_GT(h, s.transition);
        const double lwc = 0.6 * 0.5 * water.at(h);
        EXPECT_NEAR(acc.getValue(c), std::pow(lwc, 2.0 / 3.0), 1e-6) << c;
        // So value x the extinction of 1 g/m^3 is the extinction of this water.
        EXPECT_NEAR(acc.getValue(c) * extinctionPerUnitValue(s.droplets),
                    extinctionFromWater(lwc, s.droplets), 1e-6);
    }
    // The water grows with height: the top of the block is denser than its bottom.
    EXPECT_GT(acc.getValue(openvdb::Coord(5, 5, 300)),
              2.0f * acc.getValue(openvdb::Coord(5, 5, 110)));
}

TEST(CloudBase, AboveTheFirstIceTheValueIsTheLiquidsAndTheKeptIcesExtinction)
{
    const TwoLevels p;
    const CloudBaseField base(p.x.data(), p.y.data(), p.z.data(), p.x.size(), 100.0);
    const AdiabaticWater water(16.0, 880.0);
    const Glaciation ice;
    auto liquidOnly = block(4, 10, 130, 0.5f, 100.0);  // 1 km to 13 km
    auto glaciated = liquidOnly->deepCopy();
    CloudWaterSettings s;
    s.water = &water;
    shapeCloudWater(*liquidOnly, base, s);
    s.ice = &ice;
    shapeCloudWater(*glaciated, base, s);
    const double perUnit = extinctionPerUnitValue(s.droplets);
    auto liquidAcc = liquidOnly->getConstAccessor();
    auto acc = glaciated->getConstAccessor();
    int warm = 0, mixed = 0, frozen = 0;
    for (int k = 12; k <= 130; ++k) {
        const openvdb::Coord c(1, 1, k);
        const openvdb::Vec3d w = glaciated->indexToWorld(c);
        const double h = w.z() - base.at(w.x(), w.y());
        const double t = water.temperature(h), condensate = 0.6 * 0.5 * water.at(h);
        const double f = t >= -10.0 ? 0.0 : t <= -38.0 ? 1.0 : (-10.0 - t) / 28.0;
        const double sigma = extinctionFromWater((1.0 - f) * condensate, s.droplets) +
                             extinctionFromIce(f * ice.retention * condensate, 30e-6);
        EXPECT_NEAR(acc.getValue(c), sigma / perUnit, 1e-5 * sigma / perUnit) << c;
        if (f == 0.0) {
            EXPECT_EQ(acc.getValue(c), liquidAcc.getValue(c)) << "warm voxels are unchanged";
            ++warm;
        } else if (f == 1.0) {
            // A twentieth of the water as crystals: far thinner than droplets.
            EXPECT_LT(acc.getValue(c), 0.05f * liquidAcc.getValue(c)) << c;
            ++frozen;
        } else {
            ++mixed;
        }
    }
    EXPECT_GT(warm, 10);
    EXPECT_GT(mixed, 10);
    EXPECT_GT(frozen, 10);
}

TEST(CloudBase, RefusesAFieldWithoutCondensation)
{
    const float nan = std::nanf("");
    const float x = 0.0f, y = 0.0f;
    EXPECT_THROW(CloudBaseField(&x, &y, &nan, 1, 100.0), std::invalid_argument);
    const float z = 1000.0f;
    EXPECT_THROW(CloudBaseField(&x, &y, &z, 1, 0.0), std::invalid_argument);
    const float far = 1e30f;  // beyond any cell index: refused, not converted
    EXPECT_THROW(CloudBaseField(&far, &y, &z, 1, 100.0), std::invalid_argument);
}

}  // namespace cg::algo
