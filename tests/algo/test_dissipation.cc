// Clouds that dissipate: a cloud whose growth has ended keeps all its particles for `hold`,
// then loses them from its edges inward and has none left decayTime R / R0 later, its
// children with it.

#include <gtest/gtest.h>

#include <cmath>
#include <mutex>

#include "algo/mapping/Dissipation.h"

namespace cg::algo {

namespace {

/// One cloud: a level 1 copy (A = 2, R = 1.5 of R0 = 3) on a still condensation particle and
/// a level 2 copy grown on it; a primitive of 10 frames, 0.5 s each, whose 400 particles fill
/// a ball of radius 1 around (0, 0, 2) on every frame.
struct OneCloud {
    std::vector<std::uint32_t> counts = std::vector<std::uint32_t>(10, 400);
    std::vector<float> ball;
    std::vector<const float*> frames;
    SourceTable table;
    MappingSettings settings;
    std::vector<float> x{500.0f}, y{500.0f}, z{1000.0f}, condensedZ{1000.0f}, vz{0.0f};
    std::vector<std::int32_t> condensed{0};

    OneCloud()
    {
        for (int i = 0; i < 400; ++i) {  // a golden-angle spiral filling the ball evenly
            const double r = std::cbrt((i + 0.5) / 400.0), u = 1.0 - 2.0 * (i + 0.5) / 400.0;
            const double phi = 2.39996322972865332 * i, s = std::sqrt(1.0 - u * u);
            ball.insert(ball.end(), {static_cast<float>(r * s * std::cos(phi)),
                                     static_cast<float>(r * s * std::sin(phi)),
                                     static_cast<float>(2.0 + r * u)});
        }
        frames.assign(10, ball.data());
        settings.timeStep = 1.0;
        settings.scaleCoefficient = 3.0;
        settings.metresPerPrimitiveMetre = 100.0;
        settings.pastLastFrame = PastLastFrame::Hold;
        Source root;
        root.level = 1, root.parent = 0, root.startFrame = 10, root.speed = 2.0f;
        root.scale = 1.5f;
        Source child;
        child.level = 2, child.parent = 0, child.parentFluid = 7, child.startFrame = 12;
        child.speed = 1.0f, child.scale = 0.5f;
        table.sources = {root, child};
        table.condensationTaken = {1};
    }
    PrimitiveView primitive() const { return {counts.data(), frames.data(), 10, 0.5}; }
    CondensationView view() const
    {
        return {x.data(), y.data(), z.data(), condensed.data(), condensedZ.data(), 1, vz.data()};
    }

    /// The surviving particles of frame t: (source, edge distance of each) counts.
    std::vector<std::size_t> survivors(int t, const DissipationSettings& d) const
    {
        DissipationFrame f;
        f.decay = cloudDecay(table, t, primitive(), settings, d);
        f.extents = {primitiveExtent(primitive())};
        f.table = &table;
        const PrimitiveLibrary lib(primitive());
        f.library = &lib;
        f.settings = &settings;
        f.dissipation = d;
        f.frame = t;
        std::vector<std::size_t> kept(2, 0);
        std::mutex mutex;
        CloudChunkOptions o;
        o.sources = o.ids = true;
        o.chunkParticles = 64;
        forEachCloudChunk(
            table, t, view(), lib, settings,
            [&](const CloudChunk& chunk) {
                KeptParticles k;
                const CloudChunk c = chunkSurviving(chunk, f, k);
                const std::lock_guard<std::mutex> lock(mutex);
                for (std::uint64_t i = 0; i < c.count; ++i) ++kept[c.sources[i]];
            },
            o);
        return kept;
    }
};

}  // namespace

TEST(Dissipation, ACloudHoldsThenLosesEveryParticleWithinItsDecayTime)
{
    const OneCloud cloud;
    DissipationSettings d;
    d.hold = 6.0;
    d.decayTime = 40.0;
    // The root's primitive ends at 10 + 9 x 0.5 / (2 x 1) = 12.25; decay from 18.25 over
    // 40 x 1.5 / 3 = 20 frames, to 38.25.
    const std::vector<float> early =
        cloudDecay(cloud.table, 18, cloud.primitive(), cloud.settings, d);
    EXPECT_EQ(early[0], 0.0f);
    const std::vector<float> mid =
        cloudDecay(cloud.table, 28, cloud.primitive(), cloud.settings, d);
    EXPECT_NEAR(mid[0], 9.75 / 20.0, 1e-6);
    EXPECT_EQ(mid[1], mid[0]);  // the child goes with its cloud
    const std::vector<float> gone =
        cloudDecay(cloud.table, 39, cloud.primitive(), cloud.settings, d);
    EXPECT_GE(gone[0], 1.0f);

    EXPECT_EQ(cloud.survivors(18, d), (std::vector<std::size_t>{400, 400}));
    const std::vector<std::size_t> half = cloud.survivors(28, d);
    EXPECT_GT(half[0], 20u);
    EXPECT_LT(half[0], 300u);
    EXPECT_EQ(cloud.survivors(39, d), (std::vector<std::size_t>{0, 0}));
    // Monotone: each frame keeps no more than the one before.
    std::size_t before = 400;
    for (int t = 18; t <= 39; ++t) {
        const std::size_t now = cloud.survivors(t, d)[0];
        EXPECT_LE(now, before) << "frame " << t;
        before = now;
    }
}

TEST(Dissipation, AnAnvilsCopiesTakeAnvilLifeTimesLonger)
{
    const OneCloud cloud;
    DissipationSettings d;
    d.hold = 6.0;
    d.decayTime = 40.0;  // decay from 18.25 over 20 frames, as above
    d.anvilLife = 4.0;
    d.anvilBase = 5000.0;  // above the cloud: nothing changes
    EXPECT_EQ(cloud.survivors(39, d), (std::vector<std::size_t>{0, 0}));
    d.anvilBase = 900.0;  // under both copies' origins (1000 m and up): both are anvil
    // The root (level 1) ends at 18.25 + 4 x 20 = 98.25, the child (level 2) at half that.
    const std::vector<std::size_t> tower = cloud.survivors(39, d);
    EXPECT_GT(tower[0], 100u) << "the anvil outlives the tower's time";
    EXPECT_GT(tower[1], 0u);
    EXPECT_EQ(cloud.survivors(59, d)[1], 0u);
    EXPECT_GT(cloud.survivors(59, d)[0], 0u);
    EXPECT_EQ(cloud.survivors(99, d), (std::vector<std::size_t>{0, 0}));
}

TEST(Dissipation, TheEdgesGoFirst)
{
    const OneCloud cloud;
    DissipationSettings d;
    d.hold = 0.0;
    d.decayTime = 30.0;
    // The survivors are the inner particles: a ball keeps the cube of the radius it keeps.
    // The edge is measured in units of the radius holding 95% of the particles (0.983 of
    // the ball's), with a jitter of +-25%: every particle within keep 0.983 / 1.25 of the
    // centre survives, none beyond keep 0.983 / 0.75.
    const std::vector<float> f = cloudDecay(cloud.table, 20, cloud.primitive(), cloud.settings, d);
    ASSERT_NEAR(f[0], (20 - 12.25) / 15.0, 1e-6);
    const double keep = 1.0 - f[0];
    const std::size_t kept = cloud.survivors(20, d)[0];
    EXPECT_GE(kept, static_cast<std::size_t>(400 * std::pow(keep * 0.98 / 1.25, 3) * 0.9));
    EXPECT_LE(kept, static_cast<std::size_t>(400 * std::pow(keep * 0.99 / 0.75, 3) * 1.1 + 1));
}

TEST(Dissipation, BadSettingsAreRefusedNamingThem)
{
    const auto refusal = [](const DissipationSettings& d) -> std::string {
        try {
            checkDissipation(d);
        } catch (const std::invalid_argument& e) {
            return e.what();
        }
        return "";
    };
    DissipationSettings d;
    d.hold = -1.0;
    EXPECT_NE(refusal(d).find("hold"), std::string::npos);
    EXPECT_THROW(
        cloudDecay(SourceTable{}, 0, PrimitiveLibrary(PrimitiveView{}), MappingSettings{}, d),
        std::invalid_argument)
        << "the decay checks its settings";
    d.hold = 0.0;
    d.decayTime = NAN;
    EXPECT_NE(refusal(d).find("decayTime"), std::string::npos);
    d.decayTime = 0.0;
    EXPECT_EQ(refusal(d), "");
    d.anvilLife = 0.5;
    EXPECT_NE(refusal(d).find("anvilLife"), std::string::npos);
    d.anvilLife = 4.0;
    d.anvilBase = -1.0;
    EXPECT_NE(refusal(d).find("anvilBase"), std::string::npos);
}

}  // namespace cg::algo
