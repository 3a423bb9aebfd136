// Surface detail: the Perlin-Worley texture, the copy origin field, and erosion that moves
// with the copies the mapper translates.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <tbb/global_control.h>

#include "algo/mapping/Mapping.h"
#include "algo/noise/PerlinWorley.h"
#include "algo/volume/CopyOriginField.h"
#include "algo/volume/SurfaceDetail.h"
#include "algo/volume/Voxelize.h"

namespace cg::algo {

namespace {

constexpr float kSize = kPerlinWorleyTextureSize;

/// Particles on a jittered lattice filling a ball of `radius` around `centre`.
std::vector<float> ball(const double centre[3], double radius, double spacing)
{
    std::vector<float> xyz;
    for (double x = -radius; x <= radius; x += spacing)
        for (double y = -radius; y <= radius; y += spacing)
            for (double z = -radius; z <= radius; z += spacing)
                if (x * x + y * y + z * z <= radius * radius) {
                    const double j = 0.2 * spacing * std::sin(x * 0.37 + y * 0.11 + z * 0.23);
                    xyz.insert(xyz.end(), {static_cast<float>(centre[0] + x + j),
                                           static_cast<float>(centre[1] + y - j),
                                           static_cast<float>(centre[2] + z + 0.5 * j)});
                }
    return xyz;
}

}  // namespace

TEST(PerlinWorley, TextureTilesAndStaysInTheUnitInterval)
{
    double sum = 0.0, sum2 = 0.0;
    int n = 0;
    float lo = 1.0f, hi = 0.0f;
    // Steps that are exact binary fractions, so u + 64 is exact too.
    for (float u = 0.0f; u < kSize; u += 1.375f)
        for (float v = 0.0f; v < kSize; v += 2.125f)
            for (float w = 0.0f; w < kSize; w += 3.0625f) {
                const float t = perlinWorleyTexel(u, v, w);
                ASSERT_GE(t, 0.0f);
                ASSERT_LE(t, 1.0f);
                // Period: the texture edge, along every axis and from below zero.
                ASSERT_EQ(perlinWorleyTexel(u + kSize, v, w), t);
                ASSERT_EQ(perlinWorleyTexel(u, v - kSize, w), t);
                ASSERT_EQ(perlinWorleyTexel(u, v, w + 2 * kSize), t);
                lo = std::min(lo, t), hi = std::max(hi, t);
                sum += t, sum2 += double(t) * t, ++n;
            }
    const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
    // Billows and creases, not a constant: a wide spread around a middle value.
    EXPECT_GT(mean, 0.3);
    EXPECT_LT(mean, 0.7);
    EXPECT_GT(sd, 0.08);
    EXPECT_LT(lo, 0.25);
    EXPECT_GT(hi, 0.75);
}

TEST(PerlinWorley, TextureIsContinuousAcrossTexelsAndTheTileEdge)
{
    // Trilinear between texel centres: a step of 1/64 texel moves the value by at most the
    // largest texel difference / 64, far below 0.05.
    for (float u : {0.0f, 13.5f, kSize - 1.0f / 64})
        for (float f = 0.0f; f < 2.0f; f += 1.0f / 64) {
            const float a = perlinWorleyTexel(u + f, 7.25f, 30.5f);
            const float b = perlinWorleyTexel(u + f + 1.0f / 64, 7.25f, 30.5f);
            EXPECT_LT(std::abs(a - b), 0.05f) << u + f;
        }
}

TEST(PerlinWorley, FbmIsANormalisedSumOfOctaves)
{
    const double x[3] = {123.0, -456.5, 789.25};
    const double frequency = 1.0 / 100.0;
    // One octave: the texture at x frequency texels-per-cycle.
    const double t = kPerlinWorleyTexelsPerCycle * frequency;
    EXPECT_NEAR(
        perlinWorleyFbm(x, frequency, 1),
        perlinWorleyTexel(static_cast<float>(x[0] * t - kSize * std::floor(x[0] * t / kSize)),
                          static_cast<float>(x[1] * t - kSize * std::floor(x[1] * t / kSize)),
                          static_cast<float>(x[2] * t - kSize * std::floor(x[2] * t / kSize))),
        1e-6);
    for (int octaves = 1; octaves <= 6; ++octaves) {
        const float v = perlinWorleyFbm(x, frequency, octaves);
        EXPECT_GE(v, 0.0f);
        EXPECT_LE(v, 1.0f);
    }
    // Far from the origin the value is still the tile's (reduced in double).
    const double far[3] = {x[0] + 4 * kSize / t, x[1], x[2]};
    EXPECT_NEAR(perlinWorleyFbm(far, frequency, 3), perlinWorleyFbm(x, frequency, 3), 1e-5);
}

TEST(PerlinWorley, UpperBoundIsTheLargestTexelAndNoSampleExceedsIt)
{
    const float bound = perlinWorleyUpperBound();
    float largestTexel = 0.0f;
    for (int i = 0; i < kPerlinWorleyTextureSize; ++i)
        for (int j = 0; j < kPerlinWorleyTextureSize; ++j)
            for (int k = 0; k < kPerlinWorleyTextureSize; ++k)
                largestTexel =
                    std::max(largestTexel, perlinWorleyTexel(float(i), float(j), float(k)));
    // Tight: the margin is for rounding only, so the skipped voxels are nearly all that can be.
    EXPECT_GT(largestTexel, 0.5f);
    EXPECT_LE(bound - largestTexel, 2e-6f);
    // Never exceeded between texels, where the lerps round, nor by the fractal sums.
    std::uint64_t state = 12345;
    const auto uniform = [&state] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return static_cast<double>(state >> 11) * 0x1.0p-53;
    };
    for (int n = 0; n < 200000; ++n) {
        const float u = static_cast<float>(kSize * uniform()),
                    v = static_cast<float>(kSize * uniform()),
                    w = static_cast<float>(kSize * uniform());
        ASSERT_LE(perlinWorleyTexel(u, v, w), bound);
        const double x[3] = {1e4 * uniform(), 1e4 * uniform(), 1e4 * uniform()};
        ASSERT_LE(perlinWorleyFbm(x, 1.0 / 107.0, 1 + n % 8), bound);
    }
}

TEST(CopyOriginField, InsideOneCopyTheFieldIsItsOriginExactly)
{
    const double a[3] = {100.0, 200.0, 1500.0}, b[3] = {900.0, 200.0, 1500.0};
    std::vector<float> xyz = ball(a, 150.0, 20.0);
    const std::size_t na = xyz.size() / 3;
    const std::vector<float> second = ball(b, 150.0, 20.0);
    xyz.insert(xyz.end(), second.begin(), second.end());
    const std::size_t n = xyz.size() / 3;
    std::vector<std::uint32_t> sources(n, 0);
    std::fill(sources.begin() + static_cast<std::ptrdiff_t>(na), sources.end(), 1u);
    const std::vector<float> origins{101.5f, 199.25f, 1400.0f, 903.0f, 210.0f, 1390.5f};
    const double radius = 40.0;
    const CopyOriginField field(xyz.data(), sources.data(), n, origins.data(), 2, 2 * radius);

    // Every point within R of a particle has an origin: its own copy's, the copies being
    // more than 4 R apart.
    for (std::size_t i = 0; i < n; i += 7) {
        const double p[3] = {xyz[3 * i] + 0.9 * radius * std::sin(0.1 * i),
                             xyz[3 * i + 1] + 0.9 * radius * std::cos(0.1 * i) * 0.6,
                             xyz[3 * i + 2] - 0.5 * radius};
        const double lo[3] = {p[0] - 1, p[1] - 1, p[2] - 1}, hi[3] = {p[0] + 1, p[1] + 1, p[2] + 1};
        double o[3];
        ASSERT_TRUE(field.block(lo, hi).origin(p, o)) << i;
        const float* expect = &origins[3 * sources[i]];
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(o[k], expect[k], 1e-9 * std::abs(expect[k])) << i;
    }
    // Far from every particle: none.
    const double p[3] = {500.0, 200.0, 3000.0};
    double o[3];
    EXPECT_FALSE(field.block(p, p).origin(p, o));
}

TEST(CopyOriginField, WhereCopiesMeetTheOriginIsTheirParticleWeightedMean)
{
    // Two copies sharing the same particles' places: every cell holds both, so the field is
    // the mean weighted by their particle counts (2 : 1).
    const double c[3] = {0.0, 0.0, 0.0};
    const std::vector<float> one = ball(c, 100.0, 25.0);
    std::vector<float> xyz = one;
    xyz.insert(xyz.end(), one.begin(), one.end());
    xyz.insert(xyz.end(), one.begin(), one.end());
    const std::size_t m = one.size() / 3;
    std::vector<std::uint32_t> sources(3 * m, 0);
    std::fill(sources.begin() + static_cast<std::ptrdiff_t>(2 * m), sources.end(), 1u);
    const std::vector<float> origins{0.0f, 30.0f, 60.0f, 90.0f, -30.0f, 0.0f};
    const CopyOriginField field(xyz.data(), sources.data(), sources.size(), origins.data(), 2,
                                60.0);
    const double p[3] = {10.0, -20.0, 35.0};
    double o[3];
    ASSERT_TRUE(field.block(p, p).origin(p, o));
    EXPECT_NEAR(o[0], 30.0, 1e-9);
    EXPECT_NEAR(o[1], 10.0, 1e-9);
    EXPECT_NEAR(o[2], 40.0, 1e-9);
}

TEST(CopyOriginField, RefusesASourceWithoutOriginAndIsTheSameForAnyThreadCount)
{
    const double c[3] = {0.0, 0.0, 0.0};
    const std::vector<float> xyz = ball(c, 400.0, 6.0);  // more than one chunk of particles
    const std::size_t n = xyz.size() / 3;
    ASSERT_GT(n, std::size_t(1) << 16);
    std::vector<std::uint32_t> sources(n);
    for (std::size_t i = 0; i < n; ++i) sources[i] = static_cast<std::uint32_t>(i % 5);
    std::vector<float> origins(15);
    for (std::size_t k = 0; k < origins.size(); ++k)
        origins[k] = 0.1f * static_cast<float>(k * k) + 0.3f;
    EXPECT_THROW(CopyOriginField(xyz.data(), sources.data(), n, origins.data(), 4, 50.0),
                 std::invalid_argument);

    const double lo[3] = {-400, -400, -400}, hi[3] = {400, 400, 400};
    const auto sample = [&] {
        const CopyOriginField field(xyz.data(), sources.data(), n, origins.data(), 5, 50.0);
        const CopyOriginField::Block b = field.block(lo, hi);
        std::vector<double> out;
        for (double x = -300; x <= 300; x += 37.0)
            for (double y = -300; y <= 300; y += 41.0) {
                const double p[3] = {x, y, 0.3 * x - 0.2 * y};
                double o[3] = {0, 0, 0};
                if (b.origin(p, o)) out.insert(out.end(), {o[0], o[1], o[2]});
            }
        return out;
    };
    std::vector<double> one;
    {
        tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
        one = sample();
    }
    EXPECT_FALSE(one.empty());
    EXPECT_EQ(sample(), one);  // bit for bit
}

namespace {

/// A copy of a puff primitive placed by the mapper (Eq. 10-12) at frame t from a level-1 source
/// whose condensation particle stands at `at`.
struct MappedCopy {
    std::vector<float> puff;  ///< one primitive frame: a ball of 300 m
    std::vector<std::uint32_t> counts;
    std::vector<const float*> frames;
    SourceTable table;
    MappingSettings settings;

    MappedCopy()
    {
        const double c[3] = {0.0, 0.0, 150.0};
        puff = ball(c, 300.0, 30.0);
        counts = {static_cast<std::uint32_t>(puff.size() / 3),
                  static_cast<std::uint32_t>(puff.size() / 3)};
        frames = {puff.data(), puff.data()};
        Source s;
        s.level = 1;
        s.parent = 0;
        s.startFrame = 0;
        s.speed = 1.0f;
        s.scale = 1.0f;
        table.sources = {s};
        settings.pastLastFrame = PastLastFrame::Hold;
    }

    CloudParticleArrays at(int frame, const float where[3]) const
    {
        PrimitiveView p;
        p.counts = counts.data();
        p.frames = frames.data();
        p.frameCount = 2;
        const std::int32_t condensed = 0;
        CondensationView c;
        c.x = &where[0], c.y = &where[1], c.z = &where[2];
        c.condensedFrame = &condensed;
        c.condensedZ = &where[2];
        c.count = 1;
        return generateCloudParticles(table, frame, c, p, settings);
    }
};

openvdb::FloatGrid::Ptr detailed(const CloudParticleArrays& cloud, bool copyCoordinates,
                                 double amplitude)
{
    VoxelizeSettings v;
    v.voxelSize = 10.0;
    v.radius = 40.0;
    v.density = 1.0;  // the puff's inside sums past 1: an interior and a shell
    const std::size_t n = cloud.levels.size();
    auto grid = voxelizeParticles(cloud.positions.data(), n, v);
    SurfaceDetailSettings d;
    d.amplitude = amplitude;
    d.frequency = 1.5 / v.radius;
    d.octaves = 2;
    const DetailParticles particles{cloud.positions.data(), cloud.sources.data(), n,
                                    copyCoordinates ? cloud.copyOrigins.data() : nullptr,
                                    cloud.copyOrigins.size() / 3};
    erodeSurface(*grid, particles, v.radius, d);
    return grid;
}

/// The largest |a(c) - b(c + shift)| over the active voxels of both.
float largestDifference(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b,
                        const openvdb::Coord& shift)
{
    float worst = 0.0f;
    auto ab = a.getConstAccessor();
    auto bb = b.getConstAccessor();
    for (auto it = a.tree().cbeginValueOn(); it; ++it)
        worst = std::max(worst, std::abs(*it - bb.getValue(it.getCoord() + shift)));
    for (auto it = b.tree().cbeginValueOn(); it; ++it)
        worst = std::max(worst, std::abs(*it - ab.getValue(it.getCoord() - shift)));
    return worst;
}

}  // namespace

// The mapper moves a copy with its condensation particle (Eq. 12): two frames, the copy
// translated by a whole number of voxels, give the same detailed density up to the
// translation. Detail fixed in world coordinates does not (the control).
TEST(SurfaceDetail, DetailIsAttachedToTheCopyTheMapperTranslates)
{
    const MappedCopy copy;
    const float first[3] = {1000.0f, 2000.0f, 1500.0f};
    const float second[3] = {1120.0f, 1920.0f, 1750.0f};  // + (12, -8, 25) voxels
    const openvdb::Coord shift(12, -8, 25);
    const CloudParticleArrays a = copy.at(5, first), b = copy.at(9, second);
    ASSERT_EQ(a.levels.size(), copy.puff.size() / 3);
    for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(a.copyOrigins[k], first[k]);
        EXPECT_EQ(b.copyOrigins[k], second[k]);
    }

    const auto plainA = detailed(a, true, 0.0), plainB = detailed(b, true, 0.0);
    const auto attachedA = detailed(a, true, 0.8), attachedB = detailed(b, true, 0.8);
    const auto worldA = detailed(a, false, 0.8), worldB = detailed(b, false, 0.8);

    // The splats themselves translate (to float rounding of the positions).
    EXPECT_LT(largestDifference(*plainA, *plainB, shift), 1e-4f);
    // The detail is visible: it removes voxels and changes many more.
    EXPECT_LT(attachedA->activeVoxelCount(), plainA->activeVoxelCount());
    EXPECT_GT(largestDifference(*plainA, *attachedA, openvdb::Coord(0)), 0.3f);
    // Attached: the same up to the translation. In world coordinates: not.
    EXPECT_LT(largestDifference(*attachedA, *attachedB, shift), 1e-3f);
    EXPECT_GT(largestDifference(*worldA, *worldB, shift), 0.1f);
}

namespace {

/// A mapped copy's splat without detail and with amplitude 0.8.
struct PlainAndEroded {
    openvdb::FloatGrid::Ptr plain, eroded;
};
PlainAndEroded plainAndEroded(bool copyCoordinates)
{
    const MappedCopy copy;
    const float where[3] = {0.0f, 0.0f, 1000.0f};
    const CloudParticleArrays cloud = copy.at(3, where);
    return {detailed(cloud, copyCoordinates, 0.0), detailed(cloud, copyCoordinates, 0.8)};
}

}  // namespace

TEST(SurfaceDetail, ErodesOnlyTheShellAndOnlyDownward)
{
    const auto [plain, eroded] = plainAndEroded(true);
    auto acc = eroded->getConstAccessor();
    std::size_t interior = 0, shell = 0, changed = 0;
    for (auto it = plain->tree().cbeginValueOn(); it; ++it) {
        const float after = acc.getValue(it.getCoord());
        ASSERT_LE(after, *it);
        if (*it >= 1.0f) {
            ++interior;
            ASSERT_EQ(after, *it) << "the interior keeps its density";
        } else {
            ++shell;
            changed += after != *it;
        }
    }
    EXPECT_GT(interior, 0u);
    EXPECT_GT(changed, shell / 2);
    // Nothing new: every active voxel after erosion was active before.
    auto before = plain->getConstAccessor();
    for (auto it = eroded->tree().cbeginValueOn(); it; ++it)
        ASSERT_TRUE(before.isValueOn(it.getCoord()));
}

// Every shell voxel is (v - e) / (1 - e) with e = amplitude (1 - n) from its own noise value,
// bit for bit, including those eroded to nothing without evaluating the noise (v at or below
// the least erosion any noise gives).
TEST(SurfaceDetail, EveryShellVoxelIsTheErosionFormulaOfItsNoise)
{
    const auto [plain, eroded] = plainAndEroded(false);
    const double voxel = plain->voxelSize()[0], frequency = 1.5 / 40.0;
    const float leastErosion = 0.8f * (1.0f - perlinWorleyUpperBound());
    auto after = eroded->getConstAccessor();
    std::size_t skippable = 0, shell = 0;
    for (auto it = plain->tree().cbeginValueOn(); it; ++it) {
        const float v = *it;
        if (!(v < 1.0f)) continue;
        ++shell;
        skippable += v <= leastErosion;
        const openvdb::Coord c = it.getCoord();
        const double x[3] = {c.x() * voxel, c.y() * voxel, c.z() * voxel};
        const float e = 0.8f * (1.0f - perlinWorleyFbm(x, frequency, 2));
        const float expected = e >= 1.0f ? 0.0f : std::max(0.0f, (v - e) / (1.0f - e));
        ASSERT_EQ(after.getValue(c), expected) << c;
        ASSERT_EQ(after.isValueOn(c), expected > 0.0f) << c;
    }
    // Both kinds occur: the test covers the voxels whose noise is skipped.
    EXPECT_GT(skippable, 0u);
    EXPECT_GT(shell - skippable, 0u);
}

TEST(SurfaceDetail, AmplitudeZeroLeavesTheGridBitForBitAndBadSettingsAreRefused)
{
    const MappedCopy copy;
    const float where[3] = {0.0f, 0.0f, 1000.0f};
    const CloudParticleArrays cloud = copy.at(3, where);
    VoxelizeSettings v;
    v.voxelSize = 10.0;
    v.radius = 40.0;
    v.density = 1.0;
    const auto reference = voxelizeParticles(cloud.positions.data(), cloud.levels.size(), v);
    const auto off = detailed(cloud, true, 0.0);
    ASSERT_EQ(off->activeVoxelCount(), reference->activeVoxelCount());
    auto acc = off->getConstAccessor();
    for (auto it = reference->tree().cbeginValueOn(); it; ++it)
        ASSERT_EQ(acc.getValue(it.getCoord()), *it);

    const DetailParticles particles{cloud.positions.data(), cloud.sources.data(),
                                    cloud.levels.size(), cloud.copyOrigins.data(),
                                    cloud.copyOrigins.size() / 3};
    for (const auto& bad :
         {SurfaceDetailSettings{1.5, 0.01, 2}, SurfaceDetailSettings{0.5, 0.0, 2},
          SurfaceDetailSettings{0.5, 0.01, 0}, SurfaceDetailSettings{0.5, 0.01, 9}})
        EXPECT_THROW(erodeSurface(*off, particles, v.radius, bad), std::invalid_argument);
    const DetailParticles orphans{cloud.positions.data(), cloud.sources.data(), cloud.levels.size(),
                                  cloud.copyOrigins.data(), 0};
    EXPECT_THROW(erodeSurface(*off, orphans, v.radius, SurfaceDetailSettings{0.5, 0.01, 2}),
                 std::invalid_argument);
}

}  // namespace cg::algo
