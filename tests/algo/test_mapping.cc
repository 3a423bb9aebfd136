// The recursive mapping of Sec. 5.2 checked against Eq. 10-16 recomputed independently.

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <mutex>
#include <set>
#include <stdexcept>

#include <tbb/global_control.h>

#include "algo/mapping/Mapping.h"

namespace cg::algo {

namespace {

/// A small scene: a synthetic primitive, rising condensation particles, a ramp map.
struct Scene {
    static constexpr int kParticles = 40;
    static constexpr int kPrimitiveFrames = 12;

    std::vector<std::uint32_t> counts;
    std::vector<std::vector<float>> primitiveFrames;
    std::vector<const float*> framePointers;
    std::vector<float> map;
    MappingSettings settings;

    Scene()
    {
        for (int s = 0; s < kPrimitiveFrames; ++s) {
            counts.push_back(static_cast<std::uint32_t>(3 + 2 * s));
            std::vector<float> f;
            for (std::uint32_t i = 0; i < counts.back(); ++i)
                f.insert(f.end(), {std::sin(0.7f * i) * (1.0f + s), std::cos(0.3f * i) * (1.0f + s),
                                   0.5f * static_cast<float>(s) + 0.1f * static_cast<float>(i)});
            primitiveFrames.push_back(std::move(f));
        }
        for (const auto& f : primitiveFrames) framePointers.push_back(f.data());
        for (int iy = 0; iy < 8; ++iy)
            for (int ix = 0; ix < 8; ++ix) map.push_back(static_cast<float>(ix + iy) / 14.0f);
        settings.maxLevel = 3;
        settings.selectionRatio = {0.25, 0.05};
        settings.levelDelay = 4;
        settings.windowLength = {6, 5};
        settings.metresPerPrimitiveMetre = 3.0;
        settings.timeStep = 0.5;
        settings.seed = 11;
    }

    PrimitiveView primitive() const
    {
        PrimitiveView p;
        p.counts = counts.data();
        p.frames = framePointers.data();
        p.frameCount = kPrimitiveFrames;
        p.frameTime = 0.25;
        return p;
    }
    MapView mapView() const { return {map.data(), 8, 8, 100.0}; }

    /// Particle k condenses at frame 3 + k % 6 and rises 10 m per frame; its vertical speed
    /// reads 20 m/s for even k and 0 for odd k (what Level1Origin::Trail looks at).
    struct Frame {
        std::vector<float> x, y, z;
        std::vector<std::int32_t> condensed;
        std::vector<float> condensedZ;
        std::vector<float> vz;
    };
    Frame condensation(int frame) const
    {
        Frame f;
        for (int k = 0; k < kParticles; ++k) {
            f.x.push_back(20.0f * static_cast<float>(k % 8) * 5.0f);
            f.y.push_back(15.0f * static_cast<float>(k / 8) * 5.0f);
            f.z.push_back(1400.0f + 10.0f * static_cast<float>(frame));
            const int at = 3 + k % 6;
            f.condensed.push_back(frame >= at ? at : -1);
            f.condensedZ.push_back(frame >= at ? 1400.0f + 10.0f * static_cast<float>(at) : NAN);
            f.vz.push_back(k % 2 == 0 ? 20.0f : 0.0f);
        }
        return f;
    }
    static CondensationView view(const Frame& f)
    {
        return {f.x.data(),          f.y.data(), f.z.data(), f.condensed.data(),
                f.condensedZ.data(), f.x.size(), f.vz.data()};
    }
};

/// N_f(floor(A (t - t0) dt / ds)), clamped to the last frame: Eq. 11 and 13 written out.
std::uint64_t expectedClusterSize(const Scene& scene, const Source& src, int t)
{
    if (t < src.startFrame) return 0;
    const double s = src.speed * (t - src.startFrame) * scene.settings.timeStep / 0.25;
    const int f = std::min(static_cast<int>(std::floor(s)), Scene::kPrimitiveFrames - 1);
    return scene.counts[static_cast<std::size_t>(f)];
}

/// The drift past the last frame, written out: the mean of P_f(last) - P_f(last - 10) over
/// the ids present at both frames, divided by 10.
void expectedDrift(const Scene& scene, double out[3])
{
    const int last = Scene::kPrimitiveFrames - 1, first = last - 10;
    const std::uint32_t n = std::min(scene.counts[static_cast<std::size_t>(first)],
                                     scene.counts[static_cast<std::size_t>(last)]);
    for (int k = 0; k < 3; ++k) {
        double sum = 0.0;
        for (std::uint32_t i = 0; i < n; ++i)
            sum += scene.primitiveFrames[static_cast<std::size_t>(last)][3 * i + k] -
                   scene.primitiveFrames[static_cast<std::size_t>(first)][3 * i + k];
        out[k] = sum / n / 10.0;
    }
}

/// P_f[i](s) with linear interpolation, written out independently; past the last frame the
/// last frame moved by 60 (1 - exp(-(s - last) / 60)) times the drift (PastLastFrame::Drift,
/// the default).
void expectedFluid(const Scene& scene, std::uint32_t i, double s, double out[3])
{
    const int last = Scene::kPrimitiveFrames - 1;
    if (s >= last) {
        double drift[3];
        expectedDrift(scene, drift);
        const bool drifting = scene.settings.pastLastFrame == PastLastFrame::Drift;
        for (int k = 0; k < 3; ++k)
            out[k] = scene.primitiveFrames[static_cast<std::size_t>(last)][3 * i + k] +
                     (drifting ? 60.0 * (1.0 - std::exp(-(s - last) / 60.0)) * drift[k] : 0.0);
        return;
    }
    const int a = static_cast<int>(std::floor(s));
    const double w = s - a;
    for (int k = 0; k < 3; ++k) {
        const double pa = scene.primitiveFrames[static_cast<std::size_t>(a)][3 * i + k];
        const double pb = scene.primitiveFrames[static_cast<std::size_t>(a + 1)][3 * i + k];
        out[k] = pa + w * (pb - pa);
    }
}

/// Eq. 10 and 12, recursively: position of cloud particle (j, i) at frame t.
void expectedCloudParticle(const Scene& scene, const SourceTable& table, const Scene::Frame& c,
                           std::size_t j, std::uint32_t i, int t, double out[3])
{
    const Source& src = table.sources[j];
    double origin[3];
    if (src.level == 1) {
        const bool atCondensation = scene.settings.level1Origin == Level1Origin::CondensationLevel;
        // Trail: a rising particle (even k) left its copy where it was at the copy's start.
        const bool laid = scene.settings.level1Origin == Level1Origin::Trail && src.parent % 2 == 0;
        origin[0] = c.x[src.parent], origin[1] = c.y[src.parent];
        origin[2] = atCondensation ? c.condensedZ[src.parent]
                    : laid         ? 1400.0 + 10.0 * src.startFrame
                                   : c.z[src.parent];
    } else {
        expectedCloudParticle(scene, table, c, src.parent, src.parentFluid, t, origin);
    }
    double f[3];
    expectedFluid(scene, i, src.speed * (t - src.startFrame) * scene.settings.timeStep / 0.25, f);
    // A flattened copy (cloudTop 'spread') is flatten as high and 1 / sqrt(flatten) as wide.
    const double r = scene.settings.metresPerPrimitiveMetre * src.scale;
    const double across = r / std::sqrt(double{src.flatten}), up = r * src.flatten;
    for (int k = 0; k < 3; ++k) out[k] = origin[k] + (k < 2 ? across : up) * f[k];
}

struct MappingRun {
    std::vector<SourceTable> tables;  // after each frame
    std::vector<Scene::Frame> frames;
};

MappingRun run(const Scene& scene, int frames)
{
    MappingRun r;
    SourceTable table;
    int first = -1;
    for (int t = 0; t < frames; ++t) {
        r.frames.push_back(scene.condensation(t));
        for (auto f : r.frames.back().condensed)
            if (f >= 0 && (first < 0 || f < first)) first = f;
        table = stepSources(table, t, first, Scene::view(r.frames.back()), scene.mapView(),
                            scene.primitive(), scene.settings);
        r.tables.push_back(table);
    }
    return r;
}

}  // namespace

TEST(Mapping, Eq13CountsMatchTheSumOverSources)
{
    Scene scene;
    const MappingRun r = run(scene, 30);
    bool sawLevel2 = false;
    for (int t = 0; t < 30; ++t) {
        const SourceTable& table = r.tables[static_cast<std::size_t>(t)];
        std::vector<std::uint64_t> expected(3, 0);
        for (const Source& src : table.sources)
            expected[src.level - 1u] += expectedClusterSize(scene, src, t);
        EXPECT_EQ(cloudCounts(table, t, scene.primitive(), scene.settings), expected)
            << "frame " << t;
        const auto generated =
            generateCloudParticles(table, t, Scene::view(r.frames[static_cast<std::size_t>(t)]),
                                   scene.primitive(), scene.settings);
        EXPECT_EQ(generated.levels.size(), expected[0] + expected[1] + expected[2]);
        sawLevel2 = sawLevel2 || expected[1] > 0;
    }
    EXPECT_TRUE(sawLevel2);
}

TEST(Mapping, Eq14SourcesFollowTheRatioInsideTheWindowOnly)
{
    Scene scene;
    const MappingRun r = run(scene, 30);
    const int ts1 = 3;  // the first condensation frame
    for (int t = 0; t < 30; ++t) {
        const SourceTable& table = r.tables[static_cast<std::size_t>(t)];
        const auto counts = cloudCounts(table, t, scene.primitive(), scene.settings);
        std::uint64_t condensed = 0;
        for (auto f : r.frames[static_cast<std::size_t>(t)].condensed) condensed += f >= 0;
        for (int level = 1; level <= 2; ++level) {
            std::uint64_t g = 0;
            for (const Source& src : table.sources) g += src.level == level;
            const int start = ts1 + (level - 1) * scene.settings.levelDelay;
            const int end = start + windowLength(scene.settings, level);
            const std::uint64_t candidates = level == 1 ? condensed : counts[0];
            if (t >= start && t <= end &&
                level <= r.tables[static_cast<std::size_t>(std::max(t - 1, 0))].topLevel) {
                EXPECT_EQ(
                    g, static_cast<std::uint64_t>(std::floor(selectionRatio(scene.settings, level) *
                                                             static_cast<double>(candidates))))
                    << "level " << level << " frame " << t;
            }
        }
        for (const Source& src : table.sources) {
            const int start = ts1 + (src.level - 1) * scene.settings.levelDelay;
            EXPECT_GE(src.startFrame, start);
            EXPECT_LE(src.startFrame, start + windowLength(scene.settings, src.level));
        }
        EXPECT_LE(table.topLevel, scene.settings.maxLevel);
    }
}

class MappingPastLastFrame : public ::testing::TestWithParam<PastLastFrame> {};

INSTANTIATE_TEST_SUITE_P(Mapping, MappingPastLastFrame,
                         ::testing::Values(PastLastFrame::Drift, PastLastFrame::Hold));

// Frames 20 and 29 are past the primitive's end for every copy started before frame 14.
namespace {

void expectPositionsMatchTheRecursiveFormula(const Scene& scene)
{
    const MappingRun r = run(scene, 30);
    std::set<int> levelsSeen;
    for (int t : {5, 12, 20, 29}) {
        const SourceTable& table = r.tables[static_cast<std::size_t>(t)];
        const auto& c = r.frames[static_cast<std::size_t>(t)];
        const auto out =
            generateCloudParticles(table, t, Scene::view(c), scene.primitive(), scene.settings);
        std::size_t q = 0;
        for (std::size_t j = 0; j < table.sources.size(); ++j) {
            const auto n = expectedClusterSize(scene, table.sources[j], t);
            for (std::uint32_t i = 0; i < n; ++i, ++q) {
                double e[3];
                expectedCloudParticle(scene, table, c, j, i, t, e);
                for (int k = 0; k < 3; ++k)
                    ASSERT_NEAR(out.positions[3 * q + k], e[k],
                                1e-3 * std::max(1.0, std::abs(e[k])))
                        << "source " << j << " particle " << i << " frame " << t;
                EXPECT_EQ(out.sources[q], j);
                EXPECT_EQ(out.levels[q], table.sources[j].level);
                levelsSeen.insert(table.sources[j].level);
            }
        }
        EXPECT_EQ(q, out.levels.size());
    }
    EXPECT_TRUE(levelsSeen.count(1) && levelsSeen.count(2));
}

}  // namespace

TEST_P(MappingPastLastFrame, Eq10To12PositionsMatchTheRecursiveFormula)
{
    Scene scene;
    scene.settings.pastLastFrame = GetParam();
    expectPositionsMatchTheRecursiveFormula(scene);
}

TEST(Mapping, Level1CopiesCanStandAtTheirCondensationHeight)
{
    Scene scene;
    scene.settings.level1Origin = Level1Origin::CondensationLevel;
    expectPositionsMatchTheRecursiveFormula(scene);
    // The origin follows its particle across the ground and stays at the height it condensed
    // at, while the particle itself rises 10 m a frame (the paper's origin).
    const MappingRun r = run(scene, 30);
    const SourceTable& table = r.tables.back();
    const auto& c = r.frames.back();
    const auto origins =
        sourceOrigins(table, 29, Scene::view(c), scene.primitive(), scene.settings);
    scene.settings.level1Origin = Level1Origin::Particle;
    const auto paper = sourceOrigins(table, 29, Scene::view(c), scene.primitive(), scene.settings);
    int level1 = 0;
    for (std::size_t j = 0; j < table.sources.size(); ++j) {
        const Source& src = table.sources[j];
        if (src.level != 1) continue;
        ++level1;
        const int condensed = c.condensed[src.parent];
        EXPECT_EQ(origins[3 * j], c.x[src.parent]);
        EXPECT_EQ(origins[3 * j + 1], c.y[src.parent]);
        EXPECT_EQ(origins[3 * j + 2], 1400.0f + 10.0f * static_cast<float>(condensed));
        EXPECT_EQ(paper[3 * j + 2], c.z[src.parent]);
        EXPECT_EQ(paper[3 * j + 2] - origins[3 * j + 2],
                  10.0f * static_cast<float>(29 - condensed));
    }
    EXPECT_GT(level1, 0);
}

/// The highest cloud particle of every frame of a run, and of all of them.
float highestParticle(const Scene& scene, const MappingRun& r)
{
    float top = -1e30f;
    for (std::size_t t = 0; t < r.tables.size(); ++t) {
        const auto cloud =
            generateCloudParticles(r.tables[t], static_cast<int>(t), Scene::view(r.frames[t]),
                                   scene.primitive(), scene.settings);
        for (std::size_t q = 2; q < cloud.positions.size(); q += 3)
            top = std::max(top, cloud.positions[q]);
    }
    return top;
}

// cloudTop: no particle of any level rises past it at any frame, whether copies that would
// are made smaller (R < R0 fNoise, 'shrink') or flatter and wider ('spread': R = R0 fNoise,
// flatten < 1, positions as the recursive formula spreads them); without it the same scene's
// clouds do rise past it.
TEST(Mapping, NoCopyOfAnyLevelRisesPastTheCloudTop)
{
    Scene scene;
    scene.settings.level1Origin = Level1Origin::CondensationLevel;
    scene.settings.maxLevel = 3;
    const float freeTop = highestParticle(scene, run(scene, 60));
    scene.settings.cloudTop = 1560.0;
    ASSERT_GT(freeTop, scene.settings.cloudTop + 40.0f) << "the cap would not bite";
    for (const CloudTopRule rule : {CloudTopRule::Shrink, CloudTopRule::Spread}) {
        scene.settings.cloudTopRule = rule;
        const MappingRun capped = run(scene, 60);
        EXPECT_LE(highestParticle(scene, capped), 1560.0f + 1e-3f);
        const SourceTable& table = capped.tables.back();
        int smaller = 0, flatter = 0;
        std::set<int> levels;
        const Scene::Frame& c = capped.frames.back();
        for (const Source& src : table.sources) {
            levels.insert(src.level);
            flatter += src.flatten < 1.0f;
            if (src.level != 1) continue;
            const double r = scene.settings.scaleCoefficient *
                             scene.mapView().at(c.x[src.parent], c.y[src.parent]);  // Eq. 16
            smaller += src.scale < r - 1e-6;
        }
        const bool spread = rule == CloudTopRule::Spread;
        EXPECT_EQ(smaller > 0, !spread);
        EXPECT_EQ(flatter > 0, spread);
        EXPECT_EQ(levels, (std::set<int>{1, 2, 3}));  // the cap leaves the recursion room
    }
    const MappingRun early = run(scene, 30);  // what the formula check below sees
    const std::vector<Source>& sources = early.tables.back().sources;
    ASSERT_TRUE(std::any_of(sources.begin(), sources.end(),
                            [](const Source& src) { return src.flatten < 1.0f; }));
    expectPositionsMatchTheRecursiveFormula(scene);  // with the spread copies
}

TEST(Mapping, TrailCopiesStayWhereTheirRisingParticleLaidThemAndStoppedParticlesCarryTheirs)
{
    Scene scene;
    scene.settings.level1Origin = Level1Origin::Trail;
    scene.settings.trailRiseSpeed = 5.0;
    expectPositionsMatchTheRecursiveFormula(scene);
    const MappingRun r = run(scene, 30);
    const SourceTable& table = r.tables.back();
    const auto& c = r.frames.back();
    ASSERT_EQ(table.anchors.size(), 3 * table.sources.size());
    const auto origins =
        sourceOrigins(table, 29, Scene::view(c), scene.primitive(), scene.settings);
    int laid = 0, carried = 0;
    for (std::size_t j = 0; j < table.sources.size(); ++j) {
        const Source& src = table.sources[j];
        if (src.level != 1) {
            EXPECT_EQ(table.anchors[3 * j] + table.anchors[3 * j + 1] + table.anchors[3 * j + 2],
                      0.0f);
            continue;
        }
        const bool rising = src.parent % 2 == 0;  // 20 m/s against 5: laid
        (rising ? laid : carried) += 1;
        EXPECT_EQ(origins[3 * j], c.x[src.parent]);
        EXPECT_EQ(origins[3 * j + 1], c.y[src.parent]);
        // The particle is 10 m higher each frame; a laid copy stays at its start frame's height.
        const float expectedZ =
            rising ? 1400.0f + 10.0f * static_cast<float>(src.startFrame) : c.z[src.parent];
        EXPECT_EQ(origins[3 * j + 2], expectedZ)
            << "source " << j << " started at " << src.startFrame;
        if (rising && src.startFrame < 29) {
            EXPECT_LT(origins[3 * j + 2], c.z[src.parent]);
        }
    }
    EXPECT_GT(laid, 0);
    EXPECT_GT(carried, 0);
    CondensationView noSpeeds = Scene::view(c);
    noSpeeds.vz = nullptr;
    EXPECT_THROW(
        stepSources(table, 30, 3, noSpeeds, scene.mapView(), scene.primitive(), scene.settings),
        std::invalid_argument);
    // Above every particle's rise speed nothing is laid: trail places copies as the paper does.
    scene.settings.trailRiseSpeed = 25.0;
    const SourceTable riding = run(scene, 30).tables.back();
    const auto trail = sourceOrigins(riding, 29, Scene::view(c), scene.primitive(), scene.settings);
    scene.settings.level1Origin = Level1Origin::Particle;
    EXPECT_EQ(trail, sourceOrigins(riding, 29, Scene::view(c), scene.primitive(), scene.settings));
}

TEST(Mapping, ThinnedCopiesCarryEveryKthParticleFromTheirOwnPhase)
{
    Scene scene;
    scene.settings.particlesPerCopy = 4;
    scene.settings.selectionRatio = {0.5, 0.2};
    // N_f(last) = 25, so k = ceil(25 / 4) = 7.
    ASSERT_EQ(copyStride(scene.settings, scene.primitive()), 7u);
    const MappingRun r = run(scene, 30);
    std::set<int> phases;
    bool sawLevel2 = false;
    for (int t : {5, 12, 20, 29}) {
        const SourceTable& table = r.tables[static_cast<std::size_t>(t)];
        const auto& c = r.frames[static_cast<std::size_t>(t)];
        const auto out =
            generateCloudParticles(table, t, Scene::view(c), scene.primitive(), scene.settings);
        std::vector<std::uint64_t> perLevel(3, 0);
        std::size_t q = 0;
        for (std::size_t j = 0; j < table.sources.size(); ++j) {
            const Source& src = table.sources[j];
            ASSERT_LT(src.phase, 7u);
            phases.insert(src.phase);
            if (src.level >= 2) {
                // The parent cloud particle is one its parent's copy carries.
                EXPECT_EQ(src.parentFluid % 7, table.sources[src.parent].phase);
                sawLevel2 = true;
            }
            // Eq. 13 thinned: the ids phase, phase + 7, ... below N_f(s).
            const std::uint64_t nf = expectedClusterSize(scene, src, t);
            std::uint64_t n = 0;
            for (std::uint64_t id = src.phase; id < nf; id += 7, ++n, ++q) {
                double e[3];
                expectedCloudParticle(scene, table, c, j, static_cast<std::uint32_t>(id), t, e);
                for (int k = 0; k < 3; ++k)
                    ASSERT_NEAR(out.positions[3 * q + k], e[k],
                                1e-3 * std::max(1.0, std::abs(e[k])))
                        << "source " << j << " fluid id " << id << " frame " << t;
            }
            EXPECT_EQ(clusterSize(src, t, scene.settings, scene.primitive()), n);
            perLevel[src.level - 1u] += n;
        }
        EXPECT_EQ(q, out.levels.size());
        EXPECT_EQ(cloudCounts(table, t, scene.primitive(), scene.settings), perLevel);
    }
    EXPECT_TRUE(sawLevel2);
    EXPECT_GT(phases.size(), 3u);  // copies carry different particles
}

TEST(Mapping, ALevel2ClusterFollowsItsParentCloudParticle)
{
    Scene scene;
    const MappingRun r = run(scene, 30);
    const SourceTable& final = r.tables.back();
    std::size_t child = final.sources.size();
    for (std::size_t j = 0; j < final.sources.size() && child == final.sources.size(); ++j)
        if (final.sources[j].level == 2) child = j;
    ASSERT_LT(child, final.sources.size());
    const Source& src = final.sources[child];
    for (int t = src.startFrame; t < 30; ++t) {
        const auto& c = r.frames[static_cast<std::size_t>(t)];
        const auto origins =
            sourceOrigins(final, t, Scene::view(c), scene.primitive(), scene.settings);
        const auto cloud =
            generateCloudParticles(final, t, Scene::view(c), scene.primitive(), scene.settings);
        // Find the parent cloud particle (source src.parent, fluid id src.parentFluid).
        std::size_t q = 0;
        while (!(cloud.sources[q] == src.parent)) ++q;
        q += src.parentFluid;
        for (int k = 0; k < 3; ++k)
            EXPECT_EQ(origins[3 * child + k], cloud.positions[3 * q + k]) << "frame " << t;
    }
}

namespace {

/// Level 2 parents and particles drawn over many seeds: six level 1 sources started 0..5
/// frames before t, so their clusters hold 3, 7, 11, 15, 19 and 23 particles.
struct ParentDraws {
    std::vector<std::uint64_t> perParent = std::vector<std::uint64_t>(6, 0);
    std::vector<std::uint64_t> inLargest = std::vector<std::uint64_t>(23, 0);
};

ParentDraws drawParents(ParentRule rule, int seeds)
{
    Scene scene;
    const int t = 20;
    scene.settings.maxLevel = 2;
    scene.settings.firstStart = 0;
    scene.settings.levelDelay = 0;
    scene.settings.windowLength = {100};
    scene.settings.selectionRatio = {0.0, 0.1};  // no new level 1 sources; 7 level 2 a seed
    scene.settings.parentRule = rule;
    const Scene::Frame c = scene.condensation(t);
    SourceTable table;
    table.topLevel = 2;
    table.condensationTaken.assign(c.x.size(), 0);
    for (int n = 0; n < 6; ++n) {
        Source src;
        src.parent = static_cast<std::uint32_t>(n);
        src.startFrame = t - n;
        src.scale = 1.0f;
        table.sources.push_back(src);
        table.condensationTaken[static_cast<std::size_t>(n)] = 1;
    }
    ParentDraws d;
    for (int seed = 0; seed < seeds; ++seed) {
        scene.settings.seed = static_cast<std::uint64_t>(seed);
        const SourceTable next = stepSources(table, t, 0, Scene::view(c), scene.mapView(),
                                             scene.primitive(), scene.settings);
        for (std::size_t j = table.sources.size(); j < next.sources.size(); ++j) {
            const Source& src = next.sources[j];
            ++d.perParent[src.parent];
            if (src.parent == 5) ++d.inLargest[src.parentFluid];
        }
    }
    return d;
}

double chiSquareAgainstUniform(const std::vector<std::uint64_t>& counts)
{
    double total = 0.0;
    for (auto c : counts) total += static_cast<double>(c);
    const double expected = total / static_cast<double>(counts.size());
    double chi2 = 0.0;
    for (auto c : counts)
        chi2 +=
            (static_cast<double>(c) - expected) * (static_cast<double>(c) - expected) / expected;
    return chi2;
}

}  // namespace

TEST(Mapping, Eq15DrawsTheParentSourceUniformlyThenAParticleOfItUniformly)
{
    const ParentDraws d = drawParents(ParentRule::PerSource, 2000);
    std::uint64_t total = 0;
    for (auto c : d.perParent) total += c;
    EXPECT_EQ(total, 2000u * 7u);  // floor(0.1 x 78 candidates) a seed, none lost to rejection
    // Chi-square against uniform; the critical values are for p = 0.001 (5 and 22 degrees of
    // freedom), so a correct rule fails one seed set in a thousand.
    EXPECT_LT(chiSquareAgainstUniform(d.perParent), 20.52);
    EXPECT_LT(chiSquareAgainstUniform(d.inLargest), 48.27);
    // The size-weighted rule (parentRule 'particle') fails the same test by far: the largest
    // parent holds 23 / 78 of the candidates, the smallest 3 / 78.
    const ParentDraws weighted = drawParents(ParentRule::PerParticle, 2000);
    EXPECT_GT(chiSquareAgainstUniform(weighted.perParent), 1000.0);
    EXPECT_GT(weighted.perParent[5], 5 * weighted.perParent[0]);
}

TEST(Mapping, Eq16SpeedAndScaleComeFromTheMapUnderTheSource)
{
    Scene scene;
    const MappingRun r = run(scene, 30);
    const SourceTable& final = r.tables.back();
    for (std::size_t j = 0; j < final.sources.size(); ++j) {
        const Source& src = final.sources[j];
        const auto& c = r.frames[static_cast<std::size_t>(src.startFrame)];
        double x, y;
        if (src.level == 1) {
            x = c.x[src.parent];
            y = c.y[src.parent];
        } else {
            double p[3];
            expectedCloudParticle(scene, final, c, src.parent, src.parentFluid, src.startFrame, p);
            x = p[0];
            y = p[1];
        }
        const int ix = std::clamp(static_cast<int>(std::floor(x / 100.0)), 0, 7);
        const int iy = std::clamp(static_cast<int>(std::floor(y / 100.0)), 0, 7);
        const double f = scene.map[static_cast<std::size_t>(iy * 8 + ix)];
        EXPECT_FLOAT_EQ(src.scale, static_cast<float>(1.5 * f)) << "source " << j;
        EXPECT_FLOAT_EQ(src.speed, static_cast<float>(1.0 + 2.0 * f)) << "source " << j;
    }
}

TEST(Mapping, NoCandidateIsSelectedTwiceAndLevelsRespectTheirCap)
{
    Scene scene;
    scene.settings.selectionRatio = {0.9, 0.5};
    scene.settings.maxLevel = 2;
    const MappingRun r = run(scene, 30);
    const SourceTable& final = r.tables.back();
    std::set<std::pair<std::uint32_t, std::uint32_t>> seen;
    for (const Source& src : final.sources) {
        EXPECT_LE(src.level, 2);
        EXPECT_TRUE(seen.insert({src.level == 1 ? src.parent : src.parent + 1000000u,
                                 src.level == 1 ? 0u : src.parentFluid})
                        .second);
    }
}

TEST(Mapping, GenerationIsBitIdenticalForOneAndTwoThreads)
{
    Scene scene;
    const MappingRun r = run(scene, 30);
    std::vector<std::vector<float>> results;
    for (int threads : {1, 2}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        results.push_back(generateCloudParticles(r.tables.back(), 29, Scene::view(r.frames.back()),
                                                 scene.primitive(), scene.settings)
                              .positions);
    }
    EXPECT_FALSE(results[0].empty());
    EXPECT_EQ(results[0], results[1]);
}

TEST(Mapping, ChunksConcatenatedEqualTheFrameArraysForOneAndTwoThreads)
{
    Scene scene;
    const MappingRun r = run(scene, 30);
    bool sawSeveralChunks = false;
    for (int t : {5, 12, 20, 29}) {
        const SourceTable& table = r.tables[static_cast<std::size_t>(t)];
        const CondensationView c = Scene::view(r.frames[static_cast<std::size_t>(t)]);
        const auto ref = generateCloudParticles(table, t, c, scene.primitive(), scene.settings);
        const std::size_t n = ref.levels.size();
        // 7 particles a chunk: chunks straddle sources, and a source spans several chunks.
        for (std::uint64_t chunkParticles :
             {std::uint64_t{7}, std::uint64_t{1}, kCloudChunkParticles}) {
            for (int threads : {1, 2}) {
                tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
                std::vector<float> positions(3 * n, std::nanf(""));
                std::vector<std::uint8_t> levels(n, 0);
                std::vector<std::uint32_t> sources(n, 0xffffffffu);
                std::vector<int> deliveries(n, 0);
                std::mutex mutex;
                std::set<std::uint64_t> firsts;
                CloudChunkOptions o;
                o.chunkParticles = chunkParticles;
                o.levels = o.sources = true;
                const std::uint64_t total = forEachCloudChunk(
                    table, t, c, scene.primitive(), scene.settings,
                    [&](const CloudChunk& k) {
                        ASSERT_EQ(k.first % chunkParticles,
                                  0u);  // boundaries fixed by the chunk size
                        ASSERT_EQ(k.count, std::min<std::uint64_t>(chunkParticles, n - k.first));
                        ASSERT_NE(k.levels, nullptr);
                        ASSERT_NE(k.sources, nullptr);
                        std::lock_guard<std::mutex> lock(mutex);
                        firsts.insert(k.first);
                        for (std::uint64_t q = 0; q < k.count; ++q) {
                            ++deliveries[k.first + q];
                            std::memcpy(&positions[3 * (k.first + q)], k.positions + 3 * q,
                                        3 * sizeof(float));
                            levels[k.first + q] = k.levels[q];
                            sources[k.first + q] = k.sources[q];
                        }
                    },
                    o);
                EXPECT_EQ(total, n);
                EXPECT_EQ(firsts.size(), (n + chunkParticles - 1) / chunkParticles);
                sawSeveralChunks = sawSeveralChunks || firsts.size() > 1;
                for (std::size_t q = 0; q < n; ++q) ASSERT_EQ(deliveries[q], 1) << "particle " << q;
                // Bit for bit: memcmp, not float ==.
                EXPECT_EQ(
                    std::memcmp(positions.data(), ref.positions.data(), 3 * n * sizeof(float)), 0)
                    << "frame " << t << ", " << threads << " thread(s), chunks of "
                    << chunkParticles;
                EXPECT_TRUE(std::equal(levels.begin(), levels.end(), ref.levels.begin()));
                EXPECT_TRUE(std::equal(sources.begin(), sources.end(), ref.sources.begin()));

                // Positions only, straight into a frame array: the same bits, no levels/sources.
                std::vector<float> direct(3 * n, std::nanf(""));
                CloudChunkOptions into;
                into.chunkParticles = chunkParticles;
                into.positionsOut = direct.data();
                std::atomic<std::uint64_t> counted{0};
                forEachCloudChunk(
                    table, t, c, scene.primitive(), scene.settings,
                    [&](const CloudChunk& k) {
                        EXPECT_EQ(k.positions, direct.data() + 3 * k.first);
                        EXPECT_EQ(k.levels, nullptr);
                        EXPECT_EQ(k.sources, nullptr);
                        counted += k.count;
                    },
                    into);
                EXPECT_EQ(counted.load(), n);
                EXPECT_EQ(std::memcmp(direct.data(), ref.positions.data(), 3 * n * sizeof(float)),
                          0);
            }
        }
    }
    EXPECT_TRUE(sawSeveralChunks);
}

TEST(Mapping, ChunkOptionsAreChecked)
{
    Scene scene;
    const MappingRun r = run(scene, 12);
    const CondensationView c = Scene::view(r.frames.back());
    CloudChunkOptions zero;
    zero.chunkParticles = 0;
    EXPECT_THROW(
        forEachCloudChunk(r.tables.back(), 11, c, scene.primitive(), scene.settings, {}, zero),
        std::invalid_argument);
    std::vector<float> frame(3 * 1000);
    CloudChunkOptions missingLevels;
    missingLevels.positionsOut = frame.data();
    missingLevels.levels = true;
    EXPECT_THROW(forEachCloudChunk(r.tables.back(), 11, c, scene.primitive(), scene.settings, {},
                                   missingLevels),
                 std::invalid_argument);
}

}  // namespace cg::algo

namespace cg::algo {

TEST(MappingLibrary, EachSourceDrawsItsPrimitiveByItsIndexEvenly)
{
    MappingSettings s;
    s.seed = 5;
    EXPECT_EQ(primitiveOf(123, s), 0u);  // one primitive: always the first
    s.primitiveCount = 3;
    std::vector<int> counts(3, 0);
    for (std::size_t j = 0; j < 30000; ++j) {
        const std::size_t i = primitiveOf(j, s);
        ASSERT_LT(i, 3u);
        ASSERT_EQ(i, primitiveOf(j, s));
        ++counts[i];
    }
    for (int c : counts) EXPECT_NEAR(c, 10000, 500);
    // Another seed draws other primitives.
    MappingSettings other = s;
    other.seed = 6;
    int same = 0;
    for (std::size_t j = 0; j < 3000; ++j) same += primitiveOf(j, s) == primitiveOf(j, other);
    EXPECT_LT(same, 1300);
}

TEST(MappingLibrary, EachCopyPlaysItsOwnPrimitive)
{
    // Level 1 only, so the table does not depend on the primitives' positions: B is A moved
    // 50 primitive metres along x, so a copy playing B stands r 50 m east of one playing A.
    Scene scene;
    scene.settings.maxLevel = 1;
    scene.settings.primitiveCount = 2;
    std::vector<std::vector<float>> moved = scene.primitiveFrames;
    std::vector<const float*> movedPointers;
    for (auto& f : moved) {
        for (std::size_t i = 0; i < f.size(); i += 3) f[i] += 50.0f;
        movedPointers.push_back(f.data());
    }
    PrimitiveView b = scene.primitive();
    b.frames = movedPointers.data();
    const PrimitiveLibrary sameTwice(
        std::vector<PrimitiveView>{scene.primitive(), scene.primitive()});
    const PrimitiveLibrary twoShapes(std::vector<PrimitiveView>{scene.primitive(), b});

    SourceTable table;
    int first = -1;
    Scene::Frame c;
    for (int t = 0; t < 20; ++t) {
        c = scene.condensation(t);
        for (auto f : c.condensed)
            if (f >= 0 && (first < 0 || f < first)) first = f;
        table = stepSources(table, t, first, Scene::view(c), scene.mapView(), sameTwice,
                            scene.settings);
        EXPECT_EQ(table.sources.size(), stepSources(table, t, first, Scene::view(c),
                                                    scene.mapView(), twoShapes, scene.settings)
                                            .sources.size());
    }
    const auto a = generateCloudParticles(table, 19, Scene::view(c), sameTwice, scene.settings);
    const auto ab = generateCloudParticles(table, 19, Scene::view(c), twoShapes, scene.settings);
    ASSERT_EQ(a.positions.size(), ab.positions.size());
    std::set<std::size_t> played;
    for (std::size_t q = 0; q < a.sources.size(); ++q) {
        const std::size_t j = a.sources[q];
        played.insert(primitiveOf(j, scene.settings));
        const double r = scene.settings.metresPerPrimitiveMetre * table.sources[j].scale;
        const double east = primitiveOf(j, scene.settings) == 1 ? 50.0 * r : 0.0;
        ASSERT_NEAR(ab.positions[3 * q] - a.positions[3 * q], east, 1e-3 * (1.0 + east))
            << "source " << j;
        ASSERT_EQ(ab.positions[3 * q + 1], a.positions[3 * q + 1]);
        ASSERT_EQ(ab.positions[3 * q + 2], a.positions[3 * q + 2]);
    }
    EXPECT_EQ(played.size(), 2u);  // both primitives are played
}

TEST(MappingLibrary, ALibraryOfAnotherSizeThanTheTablesIsRefused)
{
    Scene scene;
    scene.settings.primitiveCount = 2;
    const Scene::Frame c = scene.condensation(5);
    EXPECT_THROW(
        stepSources({}, 5, 3, Scene::view(c), scene.mapView(), scene.primitive(), scene.settings),
        std::invalid_argument);
    EXPECT_THROW(PrimitiveLibrary(std::vector<PrimitiveView>{}), std::invalid_argument);
}

}  // namespace cg::algo
