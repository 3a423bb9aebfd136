// The glaciated outflow spread into a sheet (algo/volume/IceSpread.h).

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <tbb/global_control.h>

#include "algo/volume/IceSpread.h"

namespace cg::algo {

namespace {

constexpr double kVoxel = 100.0;

/// A grid of 100 m voxels holding 3 x 3 x 3 blocks of value 1 with their low corner at each
/// of `corners` (voxel indices).
openvdb::FloatGrid::Ptr puffs(const std::vector<openvdb::Coord>& corners)
{
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(kVoxel));
    for (const openvdb::Coord& c : corners)
        grid->denseFill(openvdb::CoordBBox(c, c.offsetBy(2)), 1.0f, true);
    return grid;
}

double layerSum(const openvdb::FloatGrid& grid, int k)
{
    double sum = 0.0;
    for (auto it = grid.cbeginValueOn(); it; ++it)
        if (it.getCoord().z() == k) sum += *it;
    return sum;
}

/// Every cloud's base at 1000 m; a parcel from 16 C there is all ice (-38 C) by about 9 km.
struct Storm {
    std::vector<float> x{0.0f}, y{0.0f}, z{1000.0f};
    CloudBaseField base{x.data(), y.data(), z.data(), 1, 500.0};
    AdiabaticWater water{16.0, 880.0};
    Glaciation ice;
    IceSpreadSettings settings;
    Storm()
    {
        settings.spread = 1500.0;  // calm: every way
        settings.outflowBottom = 9000.0;
    }
};

}  // namespace

TEST(IceSpread, TheOutflowsIceSpreadsIntoASheetKeepingEachLayersExtinction)
{
    Storm s;
    ASSERT_LT(s.water.temperature(11000.0 - 1000.0), s.ice.endC) << "the layer is all ice";
    auto grid = puffs({openvdb::Coord(0, 0, 110), openvdb::Coord(20, 5, 110)});
    const double before = layerSum(*grid, 111);
    spreadIce(*grid, s.base, s.water, s.ice, s.settings);
    EXPECT_NEAR(layerSum(*grid, 111), before, 0.01 * before);
    auto acc = grid->getConstAccessor();
    // The puffs' cores thin out and the gap between them fills: one sheet, near the Gaussian
    // of the three box passes (half-width 15 voxels: variance 3 (31^2 - 1) / 12 = 240).
    EXPECT_LT(acc.getValue(openvdb::Coord(1, 1, 111)), 0.2f);
    double gaussian = 0.0;
    const int corners[2][2] = {{0, 0}, {20, 5}};
    for (const auto& corner : corners)
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                const double dx = 11 - (corner[0] + i), dy = 3 - (corner[1] + j);
                gaussian += std::exp(-(dx * dx + dy * dy) / 480.0) / (480.0 * 3.14159265358979);
            }
    EXPECT_NEAR(acc.getValue(openvdb::Coord(11, 3, 111)), gaussian, 0.1 * gaussian);
    // Reaching about three standard deviations (45 voxels) sideways, not up.
    EXPECT_GT(acc.getValue(openvdb::Coord(-20, 1, 111)), 0.0f);
    EXPECT_FALSE(acc.isValueOn(openvdb::Coord(-60, 1, 111)));
    EXPECT_FALSE(acc.isValueOn(openvdb::Coord(1, 1, 113)));
}

TEST(IceSpread, InTheOutflowsWindTheIceStreaksAlongItKeepingItsExtinction)
{
    Storm s;
    s.settings.across = 300.0;
    for (const openvdb::Vec2d wind : {openvdb::Vec2d(12.0, 0.0), openvdb::Vec2d(-5.0, -5.0)}) {
        s.settings.directionEast = wind.x();
        s.settings.directionNorth = wind.y();
        auto grid = puffs({openvdb::Coord(0, 0, 110)});
        const double before = layerSum(*grid, 111);
        spreadIce(*grid, s.base, s.water, s.ice, s.settings);
        EXPECT_NEAR(layerSum(*grid, 111), before, 0.01 * before) << wind;
        // 20 voxels from the puff's centre along the wind and across it.
        const openvdb::Vec2d along = wind.unit() * 20.0, across(-along.y(), along.x());
        const auto at = [&](const openvdb::Vec2d& d) {
            return grid->getConstAccessor().getValue(
                openvdb::Coord(1 + static_cast<int>(std::lround(d.x())),
                               1 + static_cast<int>(std::lround(d.y())), 111));
        };
        EXPECT_GT(at(along), 5.0f * at(across)) << wind;
        EXPECT_NEAR(at(along), at(-along), 0.05f * at(along)) << "both ways along " << wind;
    }
}

TEST(IceSpread, WarmCloudAndTheGlaciatedTowerUnderTheOutflowKeepTheirShape)
{
    Storm s;
    s.settings.outflowBottom = 11500.0;
    ASSERT_LT(s.water.temperature(10000.0 - 1000.0), s.ice.endC) << "ice, but under the outflow";
    // A warm puff at 3 km, an icy one at 10 km under the outflow, one in the outflow.
    auto grid =
        puffs({openvdb::Coord(0, 0, 30), openvdb::Coord(0, 0, 100), openvdb::Coord(0, 0, 125)});
    const auto before = grid->deepCopy();
    spreadIce(*grid, s.base, s.water, s.ice, s.settings);
    auto acc = grid->getConstAccessor(), was = before->getConstAccessor();
    for (int k : {30, 31, 32, 100, 101, 102})
        for (int i = -5; i < 8; ++i) {
            const openvdb::Coord c(i, 1, k);
            EXPECT_EQ(acc.getValue(c), was.getValue(c)) << c;
            EXPECT_EQ(acc.isValueOn(c), was.isValueOn(c)) << c;
        }
    EXPECT_LT(acc.getValue(openvdb::Coord(1, 1, 126)), 0.2f) << "the outflow spreads";
}

TEST(IceSpread, TheSheetIsTheSameForAnyThreadCount)
{
    Storm s;
    s.settings.directionEast = 3.0;  // streaked along lines slanting through the layer
    s.settings.directionNorth = -2.0;
    std::vector<openvdb::FloatGrid::Ptr> grids;
    for (int threads : {1, 2, 4}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        grids.push_back(puffs({openvdb::Coord(0, 0, 108), openvdb::Coord(17, -9, 112)}));
        spreadIce(*grids.back(), s.base, s.water, s.ice, s.settings);
    }
    for (std::size_t g = 1; g < grids.size(); ++g) {
        ASSERT_EQ(grids[g]->activeVoxelCount(), grids[0]->activeVoxelCount());
        auto acc = grids[g]->getConstAccessor();
        for (auto it = grids[0]->cbeginValueOn(); it; ++it)
            ASSERT_EQ(acc.getValue(it.getCoord()), *it) << it.getCoord();
    }
}

TEST(IceSpread, FarApartCloudsSpreadAloneWithoutADenseLayerBetweenThem)
{
    Storm s;
    s.settings.maxBytes = 1 << 20;  // less than a layer spanning both
    auto both = puffs({openvdb::Coord(0, 0, 110), openvdb::Coord(400, 400, 110)});
    ASSERT_NO_THROW(spreadIce(*both, s.base, s.water, s.ice, s.settings));
    auto first = puffs({openvdb::Coord(0, 0, 110)}),
         second = puffs({openvdb::Coord(400, 400, 110)});
    spreadIce(*first, s.base, s.water, s.ice, s.settings);
    spreadIce(*second, s.base, s.water, s.ice, s.settings);
    EXPECT_EQ(both->activeVoxelCount(), first->activeVoxelCount() + second->activeVoxelCount());
    auto acc = both->getConstAccessor();
    for (const auto& alone : {first, second})
        for (auto it = alone->cbeginValueOn(); it; ++it)
            ASSERT_EQ(acc.getValue(it.getCoord()), *it) << it.getCoord();
}

TEST(IceSpread, RefusesLayersBeyondItsMemoryBeforeAllocatingThem)
{
    Storm s;
    s.settings.maxBytes = 1 << 20;
    // One sheet 600 voxels long: its layers with the margin need about 3 MB.
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(kVoxel));
    grid->denseFill(openvdb::CoordBBox(openvdb::Coord(0, 0, 110), openvdb::Coord(599, 2, 112)),
                    1.0f, true);
    const auto before = grid->activeVoxelCount();
    EXPECT_THROW(spreadIce(*grid, s.base, s.water, s.ice, s.settings), IceSpreadTooLarge);
    EXPECT_EQ(grid->activeVoxelCount(), before) << "nothing changed";
}

}  // namespace cg::algo
