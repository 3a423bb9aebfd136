// The domain warp (algo/volume/DomainWarp.h): every voxel is its warped sample, the warp
// stays within its reach, it rides with the copy the mapper moves, roughens a ball's outline
// and gives the same grid for any thread count.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <tbb/global_control.h>

#include "algo/volume/CloudMetrics.h"
#include "algo/volume/CopyTerritory.h"
#include "algo/volume/DomainWarp.h"
#include "support/GridChecksum.h"

namespace cg::algo {

namespace {

constexpr double kVoxel = 20.0;

/// A fog ball of `radius` metres around voxel `centre`: 1 inside, falling to 0 over four
/// voxels at its surface.
openvdb::FloatGrid::Ptr fogBall(double radius, const openvdb::Coord& centre = {})
{
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(kVoxel));
    const int n = static_cast<int>(std::ceil(radius / kVoxel)) + 3;
    auto acc = grid->getAccessor();
    for (int i = -n; i <= n; ++i)
        for (int j = -n; j <= n; ++j)
            for (int k = -n; k <= n; ++k) {
                const double r = std::sqrt(double(i * i + j * j + k * k)) * kVoxel;
                const double v = std::clamp(0.5 - (r - radius) / (4.0 * kVoxel), 0.0, 1.0);
                if (v > 0.0) acc.setValue(centre + openvdb::Coord(i, j, k), static_cast<float>(v));
            }
    return grid;
}

/// One copy's territory over a ball of `radius` around voxel `at`, its origin a little off
/// the centre.
CopyTerritory oneCopy(double radius, const openvdb::Coord& at)
{
    std::vector<float> xyz;
    for (double x = -radius; x <= radius; x += 40)
        for (double y = -radius; y <= radius; y += 40)
            for (double z = -radius; z <= radius; z += 40)
                if (x * x + y * y + z * z < radius * radius)
                    for (double c : {x + at[0] * kVoxel, y + at[1] * kVoxel, z + at[2] * kVoxel})
                        xyz.push_back(static_cast<float>(c));
    const std::vector<std::uint32_t> sources(xyz.size() / 3, 0);
    const float origin[3] = {static_cast<float>(at[0] * kVoxel + 35.0),
                             static_cast<float>(at[1] * kVoxel - 12.0),
                             static_cast<float>(at[2] * kVoxel + 7.0)};
    CopyTerritory territory(320.0);
    territory.add(xyz.data(), sources.data(), sources.size(), origin, 1);
    territory.finish();
    return territory;
}

DomainWarpSettings rough()
{
    DomainWarpSettings s;
    s.amplitude = 120.0;
    s.wavelength = 600.0;
    s.octaves = 4;
    s.roughness = 0.8;
    return s;
}

}  // namespace

TEST(DomainWarp, EveryVoxelIsTheSourceSampledAtItsWarpedPoint)
{
    const auto source = fogBall(500.0);
    auto warped = source->deepCopy();
    const DomainWarpSettings s = rough();
    warpVolume(*warped, nullptr, s);
    const auto acc = source->getConstAccessor();
    std::size_t checked = 0, changed = 0;
    for (auto v = warped->cbeginValueOn(); v; ++v) {
        const openvdb::Coord ijk = v.getCoord();
        const double x[3] = {ijk.x() * kVoxel, ijk.y() * kVoxel, ijk.z() * kVoxel};
        double w[3];
        domainWarpAt(x, s, w);
        float expected = 0.0f;
        openvdb::tools::BoxSampler::sample(
            acc,
            openvdb::Vec3d(ijk.x() + w[0] / kVoxel, ijk.y() + w[1] / kVoxel,
                           ijk.z() + w[2] / kVoxel),
            expected);
        ASSERT_EQ(*v, expected) << ijk;
        ASSERT_GT(*v, 0.0f);
        ++checked;
        if (*v != acc.getValue(ijk)) ++changed;
    }
    EXPECT_GT(checked, 50000u);
    EXPECT_GT(changed, checked / 10);  // the surface moved, not only the interior kept
}

TEST(DomainWarp, TheWarpStaysWithinItsReachAndAmplitudeZeroLeavesTheGrid)
{
    const DomainWarpSettings s = rough();
    const double reach = domainWarpReach(s);
    EXPECT_DOUBLE_EQ(reach, 120.0 * (1 + 0.8 + 0.64 + 0.512));
    double longest = 0.0;
    for (int i = 0; i < 20000; ++i) {
        const double x[3] = {std::fmod(i * 37.3, 5000.0), std::fmod(i * 91.7, 4000.0),
                             std::fmod(i * 13.1, 3000.0) - 1500.0};
        double w[3];
        domainWarpAt(x, s, w);
        longest = std::max(longest, std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]));
    }
    EXPECT_LE(longest, reach);
    EXPECT_GT(longest, 0.3 * reach);  // a real displacement, not a token one

    // Nothing grows farther from the ball than the reach (and the sampler's voxel).
    auto warped = fogBall(500.0);
    warpVolume(*warped, nullptr, s);
    const double outer = 500.0 + 2.0 * kVoxel + reach + std::sqrt(3.0) * kVoxel;
    for (auto v = warped->cbeginValueOn(); v; ++v)
        ASSERT_LE(v.getCoord().asVec3d().length() * kVoxel, outer) << v.getCoord();

    auto untouched = fogBall(500.0);
    DomainWarpSettings none = s;
    none.amplitude = 0.0;
    warpVolume(*untouched, nullptr, none);
    EXPECT_EQ(test::gridChecksum(*untouched), test::gridChecksum(*fogBall(500.0)));
}

TEST(DomainWarp, ItRoughensABallsOutlineSeenFromTheSide)
{
    // A smooth ball's silhouette outline has dimension about 1; a warp whose octaves stand
    // out about a third of their wavelength folds it at every scale from 800 m down to 50 m.
    const auto ball = fogBall(1200.0);
    const double smooth = measureCloud(*ball, {}).sideOutlineDimension;
    auto warped = ball->deepCopy();
    DomainWarpSettings s = rough();
    s.amplitude = 300.0;
    s.wavelength = 800.0;
    s.octaves = 5;
    warpVolume(*warped, nullptr, s);
    const double folded = measureCloud(*warped, {}).sideOutlineDimension;
    EXPECT_LT(smooth, 1.08);
    EXPECT_GT(folded, smooth + 0.08) << smooth;
}

TEST(DomainWarp, ItRidesWithItsCopyAndSwimsInWorldSpace)
{
    // The mapper moves the copy (its particles and its origin) by whole voxels and territory
    // cells: the warped grid moves with it.
    const openvdb::Coord shift(64, 0, 160);  // 1280 m, 0, 3200 m: whole 320 m cells
    const DomainWarpSettings s = rough();
    auto warped = [&](const openvdb::Coord& at, bool attached) {
        auto ball = fogBall(600.0, at);
        const CopyTerritory territory = oneCopy(700.0, at);
        warpVolume(*ball, attached ? &territory : nullptr, s);
        return ball;
    };
    const auto here = warped({}, true), there = warped(shift, true);
    const auto worldHere = warped({}, false), worldThere = warped(shift, false);
    const auto b = there->getConstAccessor();
    const auto wa = worldHere->getConstAccessor(), wb = worldThere->getConstAccessor();
    std::size_t voxels = 0, worldDiffer = 0;
    for (auto v = here->cbeginValueOn(); v; ++v) {
        ++voxels;
        ASSERT_EQ(b.getValue(v.getCoord() + shift), *v) << v.getCoord();
        if (wa.getValue(v.getCoord()) != wb.getValue(v.getCoord() + shift)) ++worldDiffer;
    }
    EXPECT_EQ(there->activeVoxelCount(), here->activeVoxelCount());
    EXPECT_GT(voxels, 50000u);
    EXPECT_GT(worldDiffer, voxels / 20) << "a world-space warp moved with the ball";
}

TEST(DomainWarp, TheGridIsTheSameForAnyThreadCount)
{
    const CopyTerritory territory = oneCopy(700.0, {});
    std::vector<std::uint64_t> sums;
    for (int threads : {1, 2, 4}) {
        const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        auto ball = fogBall(600.0);
        warpVolume(*ball, &territory, rough());
        sums.push_back(test::gridChecksum(*ball));
    }
    EXPECT_EQ(sums[0], sums[1]);
    EXPECT_EQ(sums[0], sums[2]);
}

TEST(DomainWarp, BadSettingsAreRefusedNamingTheSetting)
{
    const auto refused = [](DomainWarpSettings s, const char* name) {
        try {
            checkDomainWarpSettings(s);
            ADD_FAILURE() << name << " accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
        }
    };
    DomainWarpSettings s = rough();
    s.amplitude = -1.0;
    refused(s, "amplitude");
    s = rough();
    s.wavelength = 0.0;
    refused(s, "wavelength");
    s = rough();
    s.octaves = 9;
    refused(s, "octaves");
    s = rough();
    s.roughness = 0.0;
    refused(s, "roughness");
}

}  // namespace cg::algo
