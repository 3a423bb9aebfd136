// The mapper's motion (Eq. 10-12 differentiated) against finite differences of the positions
// it generates on neighbouring frames, matched by the particles' stable ids.

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>

#include "algo/mapping/Mapping.h"

namespace cg::algo {

namespace {

/// A primitive whose particles circle and rise smoothly over many short frames, copies on
/// three levels, and condensation particles that move at a constant, known velocity.
struct MovingScene {
    static constexpr int kParticles = 30;
    static constexpr int kPrimitiveFrames = 60;
    static constexpr float kVelocity[3] = {2.0f, -1.0f, 8.0f};  ///< condensation particles, m/s

    std::vector<std::uint32_t> counts;
    std::vector<std::vector<float>> frames;
    std::vector<const float*> pointers;
    std::vector<float> map;
    MappingSettings settings;

    MovingScene()
    {
        for (int s = 0; s < kPrimitiveFrames; ++s) {
            counts.push_back(static_cast<std::uint32_t>(4 + s));
            std::vector<float> f;
            for (std::uint32_t i = 0; i < counts.back(); ++i) {
                const double a = 0.05 * s + 0.9 * i, r = 2.0 + 0.1 * i;
                f.insert(f.end(),
                         {static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)),
                          static_cast<float>(0.3 * s + 0.05 * i)});
            }
            frames.push_back(std::move(f));
        }
        for (const auto& f : frames) pointers.push_back(f.data());
        for (int k = 0; k < 64; ++k) map.push_back(0.5f + 0.5f * static_cast<float>(k % 8) / 7.0f);
        settings.maxLevel = 3;
        settings.selectionRatio = {0.3, 0.05};
        settings.levelDelay = 10;
        settings.windowLength = {20, 20};
        settings.metresPerPrimitiveMetre = 3.0;
        settings.timeStep = 0.05;
        settings.seed = 5;
    }

    PrimitiveView primitive() const
    {
        return {counts.data(), pointers.data(), kPrimitiveFrames, 0.25};
    }

    struct Frame {
        std::vector<float> x, y, z, vx, vy, vz, condensedZ;
        std::vector<std::int32_t> condensed;
    };
    /// Particle k condenses at frame 3 + k % 6; all move at kVelocity from their start.
    Frame condensation(int frame) const
    {
        Frame f;
        const float time = static_cast<float>(frame * settings.timeStep);
        for (int k = 0; k < kParticles; ++k) {
            f.x.push_back(100.0f * static_cast<float>(k % 6) + kVelocity[0] * time);
            f.y.push_back(100.0f * static_cast<float>(k / 6) + kVelocity[1] * time);
            f.z.push_back(1400.0f + kVelocity[2] * time);
            f.vx.push_back(kVelocity[0]);
            f.vy.push_back(kVelocity[1]);
            f.vz.push_back(kVelocity[2]);
            const int at = 3 + k % 6;
            f.condensed.push_back(frame >= at ? at : -1);
            f.condensedZ.push_back(frame >= at ? 1400.0f : NAN);
        }
        return f;
    }
    static CondensationView view(const Frame& f)
    {
        CondensationView v{f.x.data(),          f.y.data(), f.z.data(), f.condensed.data(),
                           f.condensedZ.data(), f.x.size(), f.vz.data()};
        v.vx = f.vx.data();
        v.vy = f.vy.data();
        return v;
    }
};

struct Particle {
    float p[3];
    float v[3];
    std::uint32_t source;
};

/// Frame t's particles by id, with their velocities.
std::map<std::uint32_t, Particle> particlesById(const MovingScene& scene, const SourceTable& table,
                                                int t)
{
    const MovingScene::Frame c = scene.condensation(t);
    std::map<std::uint32_t, Particle> out;
    std::mutex mutex;
    CloudChunkOptions o;
    o.sources = o.velocities = o.ids = true;
    o.chunkParticles = 7;  // many chunks, cutting through copies
    forEachCloudChunk(
        table, t, MovingScene::view(c), scene.primitive(), scene.settings,
        [&](const CloudChunk& chunk) {
            const std::lock_guard<std::mutex> lock(mutex);
            for (std::uint64_t i = 0; i < chunk.count; ++i) {
                Particle q{};
                for (int k = 0; k < 3; ++k) {
                    q.p[k] = chunk.positions[3 * i + k];
                    q.v[k] = chunk.velocities[3 * i + k];
                }
                q.source = chunk.sources[i];
                if (!out.emplace(chunk.ids[i], q).second)
                    throw std::logic_error("id " + std::to_string(chunk.ids[i]) + " twice");
            }
        },
        o);
    return out;
}

/// The table after frame `last`, stepped from frame 0.
SourceTable tableAt(const MovingScene& scene, int last)
{
    SourceTable table;
    int first = -1;
    for (int t = 0; t <= last; ++t) {
        const MovingScene::Frame c = scene.condensation(t);
        for (auto f : c.condensed)
            if (f >= 0 && (first < 0 || f < first)) first = f;
        table = stepSources(table, t, first, MovingScene::view(c), {scene.map.data(), 8, 8, 100.0},
                            scene.primitive(), scene.settings);
    }
    return table;
}

/// Whether source j's copy, or a copy it rides on, reaches the primitive's last frame
/// between frames t - 1 and t + 1: its motion changes there from the shape's to the drift's,
/// a true jump of the velocity that no difference across it can follow.
bool reachesEndAround(const MovingScene& scene, const SourceTable& table, std::size_t j, int t)
{
    for (;;) {
        const Source& src = table.sources[j];
        const double rate = src.speed * scene.settings.timeStep / 0.25;
        const double last = MovingScene::kPrimitiveFrames - 1;
        if (rate * (t - 1 - src.startFrame) < last && rate * (t + 1 - src.startFrame) >= last)
            return true;
        if (src.level == 1) return false;
        j = src.parent;
    }
}

}  // namespace

/// Every particle's velocity against the central difference of its positions by id.
void expectVelocitiesMatchCentralDifferences(const MovingScene& scene)
{
    // Frames where level 1 copies grow, level 2 and 3 ride them, and early copies drift on
    // past the primitive's end (s advances 0.2 A a frame: 60 frames in 100-300).
    for (const int t : {40, 160, 400}) {
        const SourceTable table = tableAt(scene, t + 1);  // the table only appends
        const auto before = particlesById(scene, table, t - 1);
        const auto now = particlesById(scene, table, t);
        const auto after = particlesById(scene, table, t + 1);
        ASSERT_GT(now.size(), 100u);
        int levels[4] = {0, 0, 0, 0}, compared = 0;
        double worst = 0.0, shapeShare = 0.0;
        for (const auto& [id, q] : now) {
            const auto b = before.find(id), a = after.find(id);
            if (b == before.end() || a == after.end()) continue;  // appeared this frame
            if (reachesEndAround(scene, table, q.source, t)) continue;
            ASSERT_EQ(b->second.source, q.source) << "id " << id;
            ASSERT_EQ(a->second.source, q.source) << "id " << id;
            ++levels[table.sources[q.source].level];
            ++compared;
            double err = 0.0, speed = 0.0, shape = 0.0;
            for (int k = 0; k < 3; ++k) {
                const double fd = (a->second.p[k] - b->second.p[k]) / (2 * scene.settings.timeStep);
                err += (fd - q.v[k]) * (fd - q.v[k]);
                speed += fd * fd;
                const double still = q.v[k] - MovingScene::kVelocity[k];
                shape += still * still;
            }
            worst = std::max(worst, std::sqrt(err) / (std::sqrt(speed) + 0.5));
            shapeShare = std::max(shapeShare, std::sqrt(shape / (speed + 1e-9)));
        }
        EXPECT_GT(compared, 100) << "frame " << t;
        EXPECT_GT(levels[1], 0) << "frame " << t;
        if (t >= 160) {
            EXPECT_GT(levels[2], 0) << "frame " << t;
        }
        // P_f is linear between primitive frames: the central difference straddles a kink
        // or two, where the slope turns by 0.05 rad and the rise keeps its pace (0.6%
        // measured).
        EXPECT_LT(worst, 0.02) << "frame " << t;
        // The copies' own motion (their shape's; at frame 400 mostly the drift) is a large
        // part: a velocity without it would fail the bound above.
        EXPECT_GT(shapeShare, t < 400 ? 0.5 : 0.2) << "frame " << t;
    }
}

TEST(MappingMotion, VelocitiesMatchCentralDifferencesOfPositionsById)
{
    expectVelocitiesMatchCentralDifferences(MovingScene());
}

// Copies made flatter and wider under a cloud top (cloudTop 'spread') move as they stand.
TEST(MappingMotion, SpreadCopiesVelocitiesMatchTheirPositionsToo)
{
    MovingScene scene;
    scene.settings.cloudTop = 1600.0;
    scene.settings.cloudTopRule = CloudTopRule::Spread;
    const SourceTable table = tableAt(scene, 401);
    ASSERT_TRUE(std::any_of(table.sources.begin(), table.sources.end(),
                            [](const Source& src) { return src.flatten < 1.0f; }));
    expectVelocitiesMatchCentralDifferences(scene);
}

TEST(MappingMotion, IdsAreStableAcrossFramesAndUniqueWithinOne)
{
    const MovingScene scene;
    const SourceTable table = tableAt(scene, 200);
    const auto early = particlesById(scene, table, 120);
    const auto late = particlesById(scene, table, 200);
    ASSERT_GT(late.size(), early.size());
    for (const auto& [id, q] : early) {
        const auto it = late.find(id);
        ASSERT_NE(it, late.end()) << "id " << id << " vanished";
        EXPECT_EQ(it->second.source, q.source) << "id " << id;
    }
    // The ids are the prefix sums of the copies' largest clusters: dense from 0.
    const std::vector<std::uint64_t> base =
        particleIdBases(table, scene.primitive(), scene.settings);
    ASSERT_EQ(base.size(), table.sources.size());
    EXPECT_EQ(base.front(), 0u);
    for (std::size_t j = 1; j < base.size(); ++j) EXPECT_GT(base[j], base[j - 1]);
}

TEST(MappingMotion, AStandingCopyMovesWithItsShapeAloneAndAHeldOneNotAtAll)
{
    MovingScene scene;
    scene.settings.level1Origin = Level1Origin::CondensationLevel;
    scene.settings.maxLevel = 1;
    scene.settings.pastLastFrame = PastLastFrame::Hold;
    const SourceTable table = tableAt(scene, 600);
    // On the condensation level a copy's origin moves across the ground but does not rise.
    const std::vector<float> v = copyVelocities(
        table, 600, MovingScene::view(scene.condensation(600)), scene.primitive(), scene.settings);
    ASSERT_FALSE(table.sources.empty());
    for (std::size_t j = 0; j < table.sources.size(); ++j) {
        EXPECT_EQ(v[3 * j], MovingScene::kVelocity[0]);
        EXPECT_EQ(v[3 * j + 1], MovingScene::kVelocity[1]);
        EXPECT_EQ(v[3 * j + 2], 0.0f);
    }
    // At frame 600 every copy is past the primitive's end (s >= 0.2 * 570): held, its
    // particles move with the origin only.
    for (const auto& [id, q] : particlesById(scene, table, 600)) {
        EXPECT_EQ(q.v[0], MovingScene::kVelocity[0]) << "id " << id;
        EXPECT_EQ(q.v[2], 0.0f) << "id " << id;
    }
}

TEST(MappingMotion, FrameArraysDoNotTakeMotion)
{
    const MovingScene scene;
    const SourceTable table = tableAt(scene, 50);
    std::vector<float> xyz(3 * 100000);
    CloudChunkOptions o;
    o.positionsOut = xyz.data();
    o.velocities = true;
    const MovingScene::Frame c = scene.condensation(50);
    EXPECT_THROW(forEachCloudChunk(table, 50, MovingScene::view(c), scene.primitive(),
                                   scene.settings, {}, o),
                 std::invalid_argument);
}

}  // namespace cg::algo
