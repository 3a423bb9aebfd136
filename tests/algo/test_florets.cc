// Cauliflower florets (algo/volume/Florets.h, FloretDetail.h, NearbyDepth.h): the sphere
// tree's closed-form reach, lumps that roughen a sphere's outline without growing it past
// their reach, a base that stays where it was, and the same grid for any thread count.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <openvdb/openvdb.h>
#include <tbb/global_control.h>

#include "algo/volume/CopyTerritory.h"
#include "algo/volume/FloretDetail.h"
#include "algo/volume/Florets.h"
#include "algo/volume/NearbyDepth.h"
#include "support/GridChecksum.h"

namespace cg::algo {

namespace {

/// A fog ball: value 1 inside `radius` metres of `centre` (whole voxels), 0.5 on its surface,
/// falling to 0 two voxels out, on voxels of `voxel` metres.
openvdb::FloatGrid::Ptr fogBall(double radius, double voxel, const openvdb::Coord& centre = {})
{
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel));
    const int n = static_cast<int>(std::ceil(radius / voxel)) + 3;
    auto acc = grid->getAccessor();
    for (int i = -n; i <= n; ++i)
        for (int j = -n; j <= n; ++j)
            for (int k = -n; k <= n; ++k) {
                const double r = std::sqrt(double(i * i + j * j + k * k)) * voxel;
                const double v = std::clamp(0.5 - (r - radius) / (4.0 * voxel), 0.0, 1.0);
                if (v > 0.0) acc.setValue(centre + openvdb::Coord(i, j, k), static_cast<float>(v));
            }
    return grid;
}

/// One root of the first generation near (1000, 1000, 1000) m, alone.
std::vector<FloretRoot> oneRoot(const FloretSettings& s)
{
    const double lo[3] = {1000.0, 1000.0, 1000.0}, hi[3] = {1000.0, 1000.0, 1000.0};
    bool chosen = false;
    std::vector<FloretRoot> roots = gatherRoots(lo, hi, s, [&](const double*, double radius) {
        const bool take = !chosen && radius == s.radius;
        chosen = chosen || take;
        return take;
    });
    return roots;
}

double depthFrom(const FloretRoot& root, const double direction[3], double distance,
                 const FloretSettings& s)
{
    const double x[3] = {root.centre[0] + distance * direction[0],
                         root.centre[1] + distance * direction[1],
                         root.centre[2] + distance * direction[2]};
    return floretDepth(x, s, {root}, -1e9);
}

/// The spread (standard deviation, metres) over directions of the upper half (z > 0.2) of the
/// surface's distance from the origin: the outermost point along each ray where the value
/// is at least a half, at the nearest voxel.
double upperRelief(const openvdb::FloatGrid& grid)
{
    const auto acc = grid.getConstAccessor();
    double sum = 0.0, squares = 0.0;
    int count = 0;
    for (int i = 0; i < 2000; ++i) {
        const double z = 1.0 - 2.0 * (i + 0.5) / 2000.0, phi = 2.399963 * i;
        if (z < 0.2) continue;
        const double dir[3] = {std::sqrt(1 - z * z) * std::cos(phi),
                               std::sqrt(1 - z * z) * std::sin(phi), z};
        double outer = 0.0;
        for (double r = 0.0; r < 2000.0; r += 5.0) {
            const openvdb::Vec3d at =
                grid.worldToIndex(openvdb::Vec3d(r * dir[0], r * dir[1], r * dir[2]));
            const openvdb::Coord ijk(static_cast<int>(std::lround(at.x())),
                                     static_cast<int>(std::lround(at.y())),
                                     static_cast<int>(std::lround(at.z())));
            if (acc.getValue(ijk) >= 0.5f) outer = r;
        }
        sum += outer;
        squares += outer * outer;
        ++count;
    }
    const double mean = sum / count;
    return std::sqrt(std::max(0.0, squares / count - mean * mean));
}

}  // namespace

TEST(Florets, ARootsCentreLiesItsRadiusDeepAndItsChildrenReachAQuarterRadiusOut)
{
    FloretSettings s;
    s.radius = 100.0;
    s.levels = 2;
    const std::vector<FloretRoot> roots = oneRoot(s);
    ASSERT_EQ(roots.size(), 1u);
    const FloretRoot& root = roots[0];
    const double up[3] = {0.0, 0.0, 1.0}, down[3] = {0.0, 0.0, -1.0};
    EXPECT_DOUBLE_EQ(depthFrom(root, up, 0.0, s), 100.0);
    // Children (radius 50, centres 75 m out) reach 125 m from the root's centre, no further.
    double farthest = -1e30;
    for (int i = 0; i < 400; ++i) {
        const double z = 1.0 - 2.0 * (i + 0.5) / 400.0, phi = 2.399963 * i;
        const double dir[3] = {std::sqrt(1 - z * z) * std::cos(phi),
                               std::sqrt(1 - z * z) * std::sin(phi), z};
        farthest = std::max(farthest, depthFrom(root, dir, 110.0, s));
        EXPECT_LE(depthFrom(root, dir, 126.0, s), 0.0) << i;
    }
    EXPECT_GT(farthest, 0.0) << "no child stands out of the root";
    // No child points further down than 60 degrees from the horizontal.
    EXPECT_LT(depthFrom(root, down, 105.0, s), 0.0);
}

TEST(Florets, RootsAreGatheredByGenerationWhereverTheyCanReachTheBox)
{
    // Accepting every root: each generation's cells cover the box and its reach, so a point
    // of the box lies inside some lump of radius r0 (cells of 1.6 r0 hold one root each).
    FloretSettings s;
    s.radius = 100.0;
    s.levels = 3;
    const double lo[3] = {0.0, 0.0, 0.0}, hi[3] = {160.0, 160.0, 160.0};
    const auto all = gatherRoots(lo, hi, s, [](const double*, double) { return true; });
    int perGeneration[3] = {0, 0, 0};
    for (const FloretRoot& r : all) {
        ++perGeneration[r.generation];
        EXPECT_DOUBLE_EQ(r.radius, 100.0 / (1 << r.generation));
    }
    EXPECT_GT(perGeneration[0], 0);
    EXPECT_GT(perGeneration[2], perGeneration[0]);
    const auto none = gatherRoots(lo, hi, s, [](const double*, double) { return false; });
    EXPECT_TRUE(none.empty());
    const double x[3] = {80.0, 80.0, 80.0};
    EXPECT_EQ(floretDepth(x, s, none, -1e9), -1e30);
}

TEST(Florets, BadSettingsAreRefusedNamingTheSetting)
{
    FloretSettings s;
    s.levels = 7;
    EXPECT_THROW(checkFloretSettings(s), std::invalid_argument);
    s = {};
    s.radius = -1.0;
    EXPECT_THROW(checkFloretSettings(s), std::invalid_argument);
    s = {};
    s.children = 0;
    EXPECT_THROW(checkFloretSettings(s), std::invalid_argument);
}

TEST(NearbyDepth, TheDeepestPointOfABallIsItsRadiusAndFallsOffAwayFromIt)
{
    auto ball = fogBall(400.0, 20.0);
    auto sdf = openvdb::FloatGrid::create(1e6f);
    sdf->setTransform(ball->transform().copy());
    for (auto v = ball->cbeginValueOn(); v; ++v) {
        const openvdb::Vec3d p = ball->indexToWorld(v.getCoord());
        sdf->tree().setValue(v.getCoord(), static_cast<float>(p.length() - 400.0));
    }
    const NearbyDepth depth(*sdf, 50.0, 100.0);
    const double centre[3] = {0.0, 0.0, 0.0};
    EXPECT_NEAR(depth.at(centre), 400.0, 20.0);
    // At the surface the deepest point within about 100 m lies about 100 m deep.
    const double surface[3] = {400.0, 0.0, 0.0};
    EXPECT_GT(depth.at(surface), 60.0);
    EXPECT_LT(depth.at(surface), 260.0);
}

TEST(FloretDetail, LumpsRoughenABallWithoutGrowingItPastTheirReachOrLiftingItsBase)
{
    auto ball = fogBall(1000.0, 20.0);
    const double smooth = upperRelief(*ball);
    FloretSettings s;
    s.radius = 200.0;
    s.levels = 4;
    growFlorets(*ball, s, nullptr);
    // A smooth ball's surface lies within a voxel everywhere; the lumps of 200 m radius give
    // its upper half a relief of tens of metres.
    EXPECT_LT(smooth, 10.0);
    EXPECT_GT(upperRelief(*ball), 0.15 * s.radius);
    // Nothing beyond the envelope (1000 m) plus a root's tenth and its children's half radius.
    double lowest = 1e9, farthest = 0.0;
    for (auto v = ball->cbeginValueOn(); v; ++v) {
        const openvdb::Vec3d p = ball->indexToWorld(v.getCoord());
        farthest = std::max(farthest, p.length());
        lowest = std::min(lowest, p.z());
    }
    EXPECT_LE(farthest, 1000.0 + 0.6 * 200.0 + 20.0);
    // The underside does not sink and grows no lump: the base stays at the ball's bottom.
    EXPECT_NEAR(lowest, -1000.0, 40.0);
}

TEST(FloretDetail, TheGridIsTheSameForAnyThreadCountAndRadiusZeroLeavesItAlone)
{
    FloretSettings s;
    s.radius = 150.0;
    std::vector<std::uint64_t> sums;
    for (int threads : {1, 2, 4}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        auto ball = fogBall(600.0, 20.0);
        growFlorets(*ball, s, nullptr);
        sums.push_back(test::gridChecksum(*ball));
    }
    EXPECT_EQ(sums[0], sums[1]);
    EXPECT_EQ(sums[0], sums[2]);
    auto ball = fogBall(600.0, 20.0);
    const std::uint64_t before = test::gridChecksum(*ball);
    s.radius = 0.0;
    growFlorets(*ball, s, nullptr);
    EXPECT_EQ(test::gridChecksum(*ball), before);
    EXPECT_NE(sums[0], before);
}

TEST(CopyTerritory, EachCellBelongsToTheCopyWithMostParticlesTheLowerOnATie)
{
    // Cells of 100 m: copy 2 has three particles in cell (0, 0, 0), copy 1 two; in cell
    // (1, 0, 0) copies 3 and 1 have one each.
    const std::vector<float> xyz = {10, 10, 10, 20, 20,  20, 30, 30,  30, 40, 40,
                                    40, 50, 50, 50, 150, 10, 10, 160, 10, 10};
    const std::vector<std::uint32_t> sources = {2, 1, 2, 1, 2, 3, 1};
    const std::vector<float> origins = {0, 0, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
    CopyTerritory t(100.0);
    // In two chunks, the second first: the order does not matter.
    t.add(xyz.data() + 12, sources.data() + 4, 3, origins.data(), 4);
    t.add(xyz.data(), sources.data(), 4, origins.data(), 4);
    t.finish();
    const double a[3] = {50, 50, 50}, b[3] = {150, 50, 50}, none[3] = {-50, 50, 50};
    EXPECT_EQ(t.owner(a), 2);
    EXPECT_EQ(t.owner(b), 1);
    EXPECT_EQ(t.owner(none), -1);
    const double lo[3] = {0, 0, 0}, hi[3] = {199, 99, 99};
    EXPECT_EQ(t.ownersIn(lo, hi), (std::vector<std::uint32_t>{1, 2}));
    double o[3];
    t.origin(3, o);
    EXPECT_EQ(o[0], 7.0);
    EXPECT_EQ(o[2], 9.0);
    CopyTerritory bad(100.0);
    EXPECT_THROW(bad.add(xyz.data(), sources.data(), 1, origins.data(), 2), std::invalid_argument);
}

TEST(FloretDetail, LumpsRideWithTheirCopyAndSwimInWorldSpace)
{
    // One copy fills a ball; the mapper moves the copy (its particles and its origin) by a
    // whole number of voxels, territory cells and depth cells: the lumps move with it.
    const double voxel = 20.0, cell = 320.0;
    const openvdb::Coord shift(80, 0, 160);  // 1600 m, 0, 3200 m
    FloretSettings s;
    s.radius = 200.0;
    s.levels = 3;
    auto grown = [&](const openvdb::Coord& at, bool attached) {
        auto ball = fogBall(800.0, voxel, at);
        std::vector<float> xyz;
        for (double x = -800; x <= 800; x += 40)
            for (double y = -800; y <= 800; y += 40)
                for (double z = -800; z <= 800; z += 40)
                    if (x * x + y * y + z * z < 800.0 * 800.0)
                        for (double c : {x + at[0] * voxel, y + at[1] * voxel, z + at[2] * voxel})
                            xyz.push_back(static_cast<float>(c));
        const std::vector<std::uint32_t> sources(xyz.size() / 3, 0);
        const float origin[3] = {static_cast<float>(at[0] * voxel + 35.0),
                                 static_cast<float>(at[1] * voxel - 12.0),
                                 static_cast<float>(at[2] * voxel + 7.0)};
        CopyTerritory territory(cell);
        territory.add(xyz.data(), sources.data(), sources.size(), origin, 1);
        territory.finish();
        growFlorets(*ball, s, attached ? &territory : nullptr);
        return ball;
    };
    const auto here = grown({}, true), there = grown(shift, true);
    const auto worldHere = grown({}, false), worldThere = grown(shift, false);
    const auto a = here->getConstAccessor(), b = there->getConstAccessor();
    const auto wa = worldHere->getConstAccessor(), wb = worldThere->getConstAccessor();
    std::size_t voxels = 0, worldDiffer = 0;
    for (auto v = here->cbeginValueOn(); v; ++v) {
        ++voxels;
        EXPECT_EQ(b.getValue(v.getCoord() + shift), *v) << v.getCoord();
        if (wa.getValue(v.getCoord()) != wb.getValue(v.getCoord() + shift)) ++worldDiffer;
    }
    EXPECT_EQ(there->activeVoxelCount(), here->activeVoxelCount());
    EXPECT_GT(voxels, 100000u);
    EXPECT_GT(worldDiffer, voxels / 20) << "world-space lumps moved with the ball";
}

}  // namespace cg::algo
