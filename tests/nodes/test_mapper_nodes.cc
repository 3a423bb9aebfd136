// PrimitiveMapper and GenerateCloud through the engine, on the real stochastic atmosphere
// and a small synthetic primitive set.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <sstream>
#include <string>

#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include <openvdb/io/File.h>
#include "algo/volume/SurfaceDetail.h"
#include "algo/volume/Voxelize.h"
#include "core/CoreData.h"
#include "core/Error.h"
#include "core/Evaluator.h"
#include "core/Graph.h"
#include "formats/CloudPly.h"
#include "nodes/Builtin.h"
#include "nodes/data/CloudParticles.h"
#include "nodes/data/CloudSources.h"
#include "nodes/data/FogVolume.h"
#include "nodes/data/PrimitiveSet.h"
#include "nodes/data/VapourParticles.h"
#include "support/FixtureNodes.h"
#include "support/GridChecksum.h"
#include "support/TestUtil.h"

namespace cg {

namespace {

const char* kGraph = R"({
  "cloudgraph": 1, "frames": {"start": 0, "end": 130}, "timeStep": 0.2,
  "nodes": {
    "noise": {"type": "NoiseMap", "params": {"width": 24, "height": 16, "seed": 3, "centreBias": 0.5}},
    "atmosphere": {"type": "Atmosphere"},
    "emit": {"type": "VapourEmitter", "inputs": {"map": "noise.map"}},
    "rise": {"type": "ThermalIntegrator", "inputs": {"particles": "emit.particles", "atmosphere": "atmosphere.atmosphere"}},
    "condense": {"type": "Condensation", "inputs": {"particles": "rise.particles", "atmosphere": "atmosphere.atmosphere"}},
    "primitive": {"type": "TestPrimitiveSource", "params": {"frames": 20, "radius": 30}},
    "mapper": {"type": "PrimitiveMapper",
               "params": {"maxLevel": 3, "selectionRatio": [0.1, 0.02], "levelDelay": 8, "windowLength": [12, 10]},
               "inputs": {"condensation": "condense.condensation", "map": "noise.map", "primitive": "primitive.primitive"}},
    "cloud": {"type": "GenerateCloud", "inputs": {"sources": "mapper.sources", "condensation": "condense.condensation", "primitive": "primitive.primitive"}},
    "write": {"type": "WriteCloudParticles", "params": {"file": "cloud.####.ply", "every": 40}, "inputs": {"particles": "cloud.particles"}}
  }})";

class MapperNodes : public ::testing::Test {
protected:
    void SetUp() override
    {
        registerBuiltinNodes(registry);
        registerFixtureNodes(registry);
    }
    Registry registry;
};

}  // namespace

TEST_F(MapperNodes, CloudGrowsLevelByLevelAndCountsAgree)
{
    const Graph g = parseGraph(kGraph, "mapper.json", registry);
    test::TempDir out;
    EvaluatorOptions options;
    options.outDir = out.path();
    Evaluator ev(registry, options);
    std::int64_t lastCount = 0;
    int maxLevelSeen = 0;
    // GenerateCloud asked for by name: on the frames the writer (every 40) is idle, nothing
    // else would need it.
    ev.cookFrames(
        g, 0, 130, {"write", "mapper", "cloud"}, [&](int, const Evaluator::FrameOutputs& r) {
            const auto count =
                std::dynamic_pointer_cast<const IntData>(r[g.indexOf("mapper")]->at("cloudCount"));
            const auto cloud = std::dynamic_pointer_cast<const CloudParticlesData>(
                r[g.indexOf("cloud")]->at("particles"));
            ASSERT_EQ(static_cast<std::int64_t>(cloud->size()), count->value);
            EXPECT_GE(count->value, lastCount);  // sources only accumulate, N_f never decreases
            lastCount = count->value;
            for (float v : cloud->positions()) ASSERT_TRUE(std::isfinite(v));
            for (auto l : cloud->levels()) maxLevelSeen = std::max<int>(maxLevelSeen, l);
        });
    EXPECT_GT(lastCount, 0);
    EXPECT_EQ(maxLevelSeen, 3);
    EXPECT_EQ(ev.report().cookCount("mapper"), 131u);  // one step per frame
    EXPECT_TRUE(std::filesystem::exists(out / "cloud.0120.ply"));
    // The report shows the per-level counts of the mapper at every frame.
    bool sawSummary = false;
    const auto report = ev.report().toJson();
    for (const auto& r : report["records"])
        if (r["node"] == "mapper" && r["frame"] == 130) {
            sawSummary = r["values"]["summary"].get<std::string>().find("L3=") != std::string::npos;
        }
    EXPECT_TRUE(sawSummary);
}

TEST_F(MapperNodes, ACloudTopUnderEveryCopyEndsTheSelectionAndSaysSoOnce)
{
    const auto copies = [&](double cloudTop) {
        Graph g = parseGraph(kGraph, "mapper.json", registry);
        g.setParam("mapper", "cloudTop", cloudTop);
        Evaluator ev(registry, {});
        std::int64_t count = -1;
        ev.cookFrames(g, 0, 130, {"mapper"}, [&](int, const Evaluator::FrameOutputs& r) {
            count =
                std::dynamic_pointer_cast<const IntData>(r[g.indexOf("mapper")]->at("cloudCount"))
                    ->value;
        });
        return count;
    };
    ASSERT_GT(copies(0.0), 0);
    std::ostringstream log;
    auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(log);
    spdlog::default_logger()->sinks().push_back(sink);
    const std::int64_t capped = copies(1.0);  // a metre above sea level: under every origin
    auto& sinks = spdlog::default_logger()->sinks();
    sinks.erase(std::remove(sinks.begin(), sinks.end(), sink), sinks.end());
    EXPECT_EQ(capped, 0);
    const std::string text = log.str();
    const std::string said = "cloudTop 1 m refused every first copy";
    const auto first = text.find(said);
    EXPECT_NE(first, std::string::npos) << text;
    EXPECT_EQ(text.find(said, first + said.size()), std::string::npos) << "once";
}

TEST_F(MapperNodes, CloudIsBitIdenticalForOneAndTwoThreads)
{
    std::vector<std::vector<float>> results;
    for (int threads : {1, 2}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        const Graph g = parseGraph(kGraph, "mapper.json", registry);
        Evaluator ev(registry, {});
        const auto cloud = std::dynamic_pointer_cast<const CloudParticlesData>(
            ev.pull(g, "cloud", 125)->at("particles"));
        results.push_back(cloud->positions());
    }
    EXPECT_FALSE(results[0].empty());
    EXPECT_EQ(results[0], results[1]);
}

TEST_F(MapperNodes, EvaporateBelowBaseDropsExactlyTheParticlesUnderTheLowestCondensationHeight)
{
    Graph g = parseGraph(kGraph, "mapper.json", registry);
    g.setParam("primitive", "sink",
               1.0);  // the copies hang below their origins, as real puffs' wakes
    g.setParam("mapper", "level1Origin", std::string("condensationLevel"));  // origins on the level
    Evaluator ev(registry, {});
    const int frame = 125;
    const auto full = std::dynamic_pointer_cast<const CloudParticlesData>(
        ev.pull(g, "cloud", frame)->at("particles"));
    const auto condensation = std::dynamic_pointer_cast<const CondensationData>(
        ev.pull(g, "condense", frame)->at("condensation"));
    float base = INFINITY;
    for (std::size_t i = 0; i < condensation->particles->size(); ++i)
        if (condensation->condensed(i)) base = std::min(base, condensation->condensedHeight[i]);
    ASSERT_TRUE(std::isfinite(base));
    std::vector<float> expected;  // the full frame's particles at or above the base, in order
    for (std::size_t i = 0; i < full->size(); ++i)
        if (full->positions()[3 * i + 2] >= base)
            expected.insert(expected.end(), &full->positions()[3 * i],
                            &full->positions()[3 * i] + 3);
    ASSERT_LT(expected.size(),
              3 * full->size());  // the copies hang below the base: the test can fail

    g.setParam("cloud", "evaporateBelowBase", true);
    const auto kept = std::dynamic_pointer_cast<const CloudParticlesData>(
        ev.pull(g, "cloud", frame)->at("particles"));
    EXPECT_EQ(std::vector<float>(kept->positions()), expected);
    ASSERT_EQ(kept->levels().size(), expected.size() / 3);
    for (std::size_t i = 0; i < kept->size(); ++i) EXPECT_GE(kept->positions()[3 * i + 2], base);
}

TEST_F(MapperNodes, PrimitiveSubsetKeepsEveryKthParticleOnItsTrajectory)
{
    const Graph g = parseGraph(R"({"cloudgraph": 1, "nodes": {
        "full": {"type": "TestPrimitiveSource", "params": {"frames": 12, "radius": 30}},
        "thin": {"type": "PrimitiveSubset", "inputs": {"primitive": "full.primitive"}, "params": {"particles": 7}}}})",
                               "subset.json", registry);
    Evaluator ev(registry, {});
    const auto full =
        std::dynamic_pointer_cast<const PrimitiveSetData>(ev.pull(g, "full", 0)->at("primitive"));
    const auto thin =
        std::dynamic_pointer_cast<const PrimitiveSetData>(ev.pull(g, "thin", 0)->at("primitive"));
    const std::uint32_t last = full->count(full->frames() - 1);
    ASSERT_GT(last, 7u);
    const std::uint32_t k = (last + 6) / 7;  // ceil(N_f(last) / K)
    ASSERT_EQ(thin->frames(), full->frames());
    EXPECT_EQ(thin->frameTime, full->frameTime);
    for (int s = 0; s < full->frames(); ++s) {
        ASSERT_EQ(thin->count(s), (full->count(s) + k - 1) / k) << "frame " << s;
        for (std::uint32_t id = 0; id < thin->count(s); ++id)
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(thin->frame(s)[3 * id + c], full->frame(s)[3 * (id * k) + c]);
    }
    EXPECT_LE(thin->count(thin->frames() - 1), 7u);
}

TEST_F(MapperNodes, LogTextRecordsTheLinesItPrints)
{
    const Graph withLog = parseGraph(
        std::string(kGraph).insert(
            std::string(kGraph).rfind("}}"),
            R"(, "log": {"type": "LogText", "inputs": {"text": "mapper.summary"}, "params": {"every": 40}})"),
        "mapper.json", registry);
    Evaluator ev(registry, {});
    ev.cookFrames(withLog, 0, 130, {"log"});
    int printed = 0;
    const auto report = ev.report().toJson();
    for (const auto& r : report["records"]) {
        if (r["node"] != "log") continue;
        const std::string line = r.value("values", nlohmann::json::object()).value("logged", "");
        const int frame = r["frame"].get<int>();
        if (frame % 40 == 0) {
            EXPECT_EQ(line.rfind("frame " + std::to_string(frame) + ": L1=", 0), 0u) << line;
            ++printed;
        } else {
            EXPECT_EQ(line, "");
        }
    }
    EXPECT_EQ(printed, 4);  // frames 0, 40, 80, 120
}

// The Voxelizer takes GenerateCloud's particles chunk by chunk as they are generated, with no
// frame array; its grid must be the one made from the frame's arrays, bit for bit, with and
// without evaporation (which drops particles from the streamed chunks).
TEST_F(MapperNodes, StreamedVoxelizationEqualsTheFrameArrayPathBitForBit)
{
    std::string text = kGraph;
    const std::string write = R"("write": {)";
    text.replace(text.find(write), write.size(),
                 R"("vox": {"type": "Voxelizer", "inputs": {"particles": "cloud.particles"},
                            "params": {"voxelSize": 4, "radius": 14}},
                    "write": {)");
    Graph g = parseGraph(text, "mapper.json", registry);
    g.setParam("primitive", "sink", 1.0);
    g.setParam("mapper", "level1Origin", std::string("condensationLevel"));
    const int frame = 125;
    for (const bool evaporate : {false, true}) {
        g.setParam("cloud", "evaporateBelowBase", evaporate);
        Evaluator ev(registry, {});
        const auto streamed =
            std::dynamic_pointer_cast<const FogVolumeData>(ev.pull(g, "vox", frame)->at("volume"));
        // GenerateCloud keeps nothing: this pull makes a fresh frame, read here as arrays.
        const auto cloud = std::dynamic_pointer_cast<const CloudParticlesData>(
            ev.pull(g, "cloud", frame)->at("particles"));
        const auto& a = cloud->arrays();
        ASSERT_GT(cloud->size(), 10000u);
        algo::VoxelizeSettings s;
        s.voxelSize = 4.0;
        s.radius = 14.0;
        s.kernel = algo::VoxelKernel::Gaussian;
        auto expected = algo::voxelizeParticles(a.positions.data(), cloud->size(), s);
        algo::SurfaceDetailSettings detail;
        detail.amplitude = 0.8;
        detail.frequency = 1.5 / s.radius;
        detail.octaves = 2;
        algo::erodeSurface(
            *expected,
            algo::DetailParticles{a.positions.data(), a.sources.data(), cloud->size(),
                                  a.copyOrigins.data(), a.copyOrigins.size() / 3},
            s.radius, detail);
        EXPECT_EQ(streamed->grid->metaValue<openvdb::Int64>("particle_count"),
                  static_cast<openvdb::Int64>(cloud->size()));
        EXPECT_EQ(streamed->grid->activeVoxelCount(), expected->activeVoxelCount());
        EXPECT_EQ(test::gridChecksum(*streamed->grid), test::gridChecksum(*expected))
            << "evaporate " << evaporate;
    }
}

// WriteCloudParticles writes GenerateCloud's frame chunk by chunk, each at its place, with no
// frame array; the file must be the one written from the frame's arrays, byte for byte, with
// and without evaporation (which changes every chunk's count), for 1 and 2 threads.
TEST_F(MapperNodes, StreamedPlyEqualsThePlyOfTheFrameArraysByteForByte)
{
    Graph g = parseGraph(kGraph, "mapper.json", registry);
    g.setParam("primitive", "sink", 1.0);
    g.setParam("mapper", "level1Origin", std::string("condensationLevel"));
    g.setParam("write", "every", 1);
    g.setParam("write", "motion", false);  // the arrays hold no motion
    const int frame = 125;
    for (const bool evaporate : {false, true})
        for (const int threads : {1, 2}) {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
            g.setParam("cloud", "evaporateBelowBase", evaporate);
            test::TempDir out;
            EvaluatorOptions options;
            options.outDir = out.path();
            Evaluator ev(registry, options);
            ev.pull(g, "write", frame);
            const std::string streamed = test::readFile(out / "cloud.0125.ply");
            // GenerateCloud keeps nothing: this pull makes a fresh frame, read here as arrays.
            const auto cloud = std::dynamic_pointer_cast<const CloudParticlesData>(
                ev.pull(g, "cloud", frame)->at("particles"));
            const auto& a = cloud->arrays();
            ASSERT_GT(cloud->size(), 10000u);
            formats::writeCloudPly(out / "arrays.ply", cloud->size(), a.positions.data(),
                                   a.levels.data(), a.sources.data(), "cloud particles, frame 125");
            const std::string expected = test::readFile(out / "arrays.ply");
            EXPECT_EQ(streamed.size(), expected.size()) << "evaporate " << evaporate;
            EXPECT_TRUE(streamed == expected)
                << "evaporate " << evaporate << ", threads " << threads;
        }
}

// GenerateCloud's particles move as their positions change from frame to frame: in a wind
// that turns and strengthens with height, with evaporation, every particle present on frames
// t - 1, t and t + 1 (matched by id) has a velocity within 2% (plus 0.3 m/s) of the central
// difference. The condensation particles' own sideways speed is the wind of the step before
// (explicit Euler), so differences across a step differ from it by the wind's change over
// one step's rise.
TEST_F(MapperNodes, GeneratedParticlesMoveAsTheirPositionsChangeFrameToFrame)
{
    std::string text = kGraph;
    const std::string calm = R"("atmosphere": {"type": "Atmosphere"})";
    text.replace(text.find(calm), calm.size(),
                 R"("atmosphere": {"type": "Atmosphere", "params": {"wind": "layers",
                    "windHeights": [0, 4000], "windSpeeds": [4, 12],
                    "windDirections": [270, 230]}})");
    Graph g = parseGraph(text, "mapper.json", registry);
    g.setParam("cloud", "evaporateBelowBase", true);
    Evaluator ev(registry, EvaluatorOptions{});
    struct Moving {
        float p[3], v[3];
    };
    const auto frame = [&](int t) {
        const auto cloud = std::dynamic_pointer_cast<const CloudParticlesData>(
            ev.pull(g, "cloud", t)->at("particles"));
        EXPECT_TRUE(cloud->hasMotion());
        std::map<std::uint32_t, Moving> out;
        std::mutex mutex;
        cloud->forEachChunk(
            [&](const algo::CloudChunk& c) {
                const std::lock_guard<std::mutex> lock(mutex);
                for (std::uint64_t i = 0; i < c.count; ++i) {
                    Moving m{};
                    std::copy_n(c.positions + 3 * i, 3, m.p);
                    std::copy_n(c.velocities + 3 * i, 3, m.v);
                    EXPECT_TRUE(out.emplace(c.ids[i], m).second) << "id " << c.ids[i];
                }
            },
            CloudChunkFields{false, false, true, true});
        return out;
    };
    const int t = 110;
    const auto before = frame(t - 1), now = frame(t), after = frame(t + 1);
    ASSERT_GT(now.size(), 5000u);
    std::size_t compared = 0, off = 0;
    double sideways = 0.0;
    for (const auto& [id, q] : now) {
        const auto b = before.find(id), a = after.find(id);
        if (b == before.end() || a == after.end()) continue;
        ++compared;
        double err = 0.0, speed = 0.0;
        for (int k = 0; k < 3; ++k) {
            const double fd = (a->second.p[k] - b->second.p[k]) / (2 * 0.2);
            err += (fd - q.v[k]) * (fd - q.v[k]);
            speed += fd * fd;
        }
        sideways = std::max(sideways, std::hypot(double(q.v[0]), double(q.v[1])));
        if (std::sqrt(err) > 0.02 * std::sqrt(speed) + 0.3) ++off;
    }
    EXPECT_GT(compared, now.size() / 2);
    EXPECT_GT(sideways, 4.0);  // the wind moves them
    // A copy that reaches its primitive's last frame between t - 1 and t + 1 changes its
    // velocity there (from its shape's motion to the drift): those few may differ.
    EXPECT_LT(off, compared / 50) << off << " of " << compared;
}

// CloudVelocity and WriteVDB: the file holds 'density' and a Vec3f 'vel' on the same voxels,
// each voxel moving as the particles around it (its velocity within the range of theirs, and
// their mean in the mean); a velocity made from another volume is refused naming the port.
TEST_F(MapperNodes, WriteVdbWritesTheVelocityGridBesideTheDensity)
{
    std::string text = kGraph;
    const std::string write = R"("write": {)";
    text.replace(text.find(write), write.size(),
                 R"("vox": {"type": "Voxelizer", "inputs": {"particles": "cloud.particles"},
                            "params": {"voxelSize": 8, "radius": 14}},
                    "coarse": {"type": "Voxelizer", "inputs": {"particles": "cloud.particles"},
                            "params": {"voxelSize": 16, "radius": 14}},
                    "vel": {"type": "CloudVelocity", "params": {"cellSize": 28},
                            "inputs": {"particles": "cloud.particles", "volume": "VOLUME"}},
                    "vdb": {"type": "WriteVDB", "params": {"file": "v.####.vdb"},
                            "inputs": {"volume": "vox.volume", "velocity": "vel.velocity"}},
                    "write": {)");
    const auto graphWith = [&](const std::string& volume) {
        std::string t = text;
        t.replace(t.find("VOLUME"), 6, volume);
        return parseGraph(t, "mapper.json", registry);
    };
    const Graph g = graphWith("vox.volume");
    test::TempDir out;
    EvaluatorOptions options;
    options.outDir = out.path();
    Evaluator ev(registry, options);
    const int frame = 110;
    ev.pull(g, "vdb", frame);
    openvdb::io::File file((out / "v.0110.vdb").string());
    file.open();
    const auto density = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("density"));
    const auto vel = openvdb::gridPtrCast<openvdb::Vec3fGrid>(file.readGrid("vel"));
    file.close();
    ASSERT_TRUE(density && vel);
    EXPECT_TRUE(vel->tree().hasSameTopology(density->tree()));
    EXPECT_EQ(vel->transform(), density->transform());
    EXPECT_GT(vel->activeVoxelCount(), 1000u);

    const auto cloud = std::dynamic_pointer_cast<const CloudParticlesData>(
        ev.pull(g, "cloud", frame)->at("particles"));
    openvdb::Vec3d lo(1e30), hi(-1e30), sum(0.0);
    std::size_t n = 0;
    std::mutex mutex;
    cloud->forEachChunk(
        [&](const algo::CloudChunk& c) {
            const std::lock_guard<std::mutex> lock(mutex);
            for (std::uint64_t i = 0; i < c.count; ++i, ++n)
                for (int k = 0; k < 3; ++k) {
                    lo[k] = std::min(lo[k], double(c.velocities[3 * i + k]));
                    hi[k] = std::max(hi[k], double(c.velocities[3 * i + k]));
                    sum[k] += c.velocities[3 * i + k];
                }
        },
        CloudChunkFields{false, false, true, false});
    openvdb::Vec3d voxelSum(0.0);
    for (auto it = vel->cbeginValueOn(); it; ++it)
        for (int k = 0; k < 3; ++k) {
            EXPECT_GE((*it)[k], lo[k] - 1e-3);
            EXPECT_LE((*it)[k], hi[k] + 1e-3);
            voxelSum[k] += (*it)[k];
        }
    // The rise dominates: the voxels' mean rise is the particles' within 20%.
    const double rise = sum[2] / n, voxelRise = voxelSum[2] / vel->activeVoxelCount();
    EXPECT_GT(rise, 1.0);
    EXPECT_NEAR(voxelRise, rise, 0.2 * rise);

    try {
        ev.pull(graphWith("coarse.volume"), "vdb", frame);
        ADD_FAILURE() << "a velocity on another transform was written";
    } catch (const CookError& e) {
        EXPECT_TRUE(e.inputFault());
        EXPECT_NE(std::string(e.what()).find("/nodes/vdb/inputs/velocity"), std::string::npos)
            << e.what();
    }
}

// Particles that are not the mapper's carry no motion: CloudVelocity says so, naming its port.
TEST_F(MapperNodes, CloudVelocityRefusesParticlesWithoutMotion)
{
    std::string text = kGraph;
    const std::string write = R"("write": {)";
    text.replace(
        text.find(write), write.size(),
        R"("points": {"type": "VapourPoints", "inputs": {"condensation": "condense.condensation"}},
                    "vox": {"type": "Voxelizer", "inputs": {"particles": "points.particles"},
                            "params": {"voxelSize": 8, "radius": 14}},
                    "vel": {"type": "CloudVelocity",
                            "inputs": {"particles": "points.particles", "volume": "vox.volume"}},
                    "write": {)");
    const Graph g = parseGraph(text, "mapper.json", registry);
    Evaluator ev(registry, {});
    try {
        ev.pull(g, "vel", 110);
        ADD_FAILURE() << "vapour points were given a velocity";
    } catch (const CookError& e) {
        EXPECT_TRUE(e.inputFault());
        EXPECT_NE(std::string(e.what()).find("carry no motion"), std::string::npos) << e.what();
    }
}

// Clouds that dissipate through the engine: the frame's arrays are its streamed chunks in
// order, and once every cloud's decay is over nothing is left.
TEST_F(MapperNodes, DissipatingCloudsThinThenVanishAndTheirArraysAreTheirChunks)
{
    // A primitive of 4 frames (1 s each) grows within 15 frames of 0.2 s at A >= 1; with
    // decayTime 4 s a cloud is gone at most 20 frames later. The last sources start by
    // frame 125, so by frame 200 nothing is left.
    std::string text = kGraph;
    text.replace(text.find(R"("end": 130)"), 10, R"("end": 200)");
    text.replace(text.find(R"("frames": 20)"), 12, R"("frames": 4)");
    Graph g = parseGraph(text, "mapper.json", registry);
    g.setParam("cloud", "dissipate", true);
    g.setParam("cloud", "hold", 0.0);
    g.setParam("cloud", "decayTime", 4.0);
    Evaluator ev(registry, {});
    const auto cloudAt = [&](int t) {
        return std::dynamic_pointer_cast<const CloudParticlesData>(
            ev.pull(g, "cloud", t)->at("particles"));
    };
    const auto streamed = [](const CloudParticlesData& c) {
        std::map<std::uint64_t, std::vector<float>> chunks;
        std::mutex mutex;
        c.forEachChunk(
            [&](const algo::CloudChunk& k) {
                const std::lock_guard<std::mutex> lock(mutex);
                chunks[k.first].assign(k.positions, k.positions + 3 * k.count);
            },
            CloudChunkFields{});
        std::vector<float> all;
        for (const auto& [first, xyz] : chunks) all.insert(all.end(), xyz.begin(), xyz.end());
        return all;
    };
    std::size_t peak = 0, peakFrame = 0;
    for (int t = 90; t <= 200; t += 5) {
        const std::size_t n = cloudAt(t)->size();
        if (n > peak) peak = n, peakFrame = static_cast<std::size_t>(t);
    }
    ASSERT_GT(peak, 1000u);
    const auto thinning = cloudAt(static_cast<int>(peakFrame) + 10);
    const std::vector<float> chunks = streamed(*thinning);
    const auto& arrays = thinning->arrays();
    ASSERT_EQ(chunks.size(), arrays.positions.size());
    EXPECT_TRUE(std::equal(chunks.begin(), chunks.end(), arrays.positions.begin()));
    EXPECT_LT(thinning->size(), peak);

    g.setParam("cloud", "dissipate", false);
    EXPECT_GT(cloudAt(200)->size(), peak);  // without it the clouds last
    g.setParam("cloud", "dissipate", true);
    EXPECT_EQ(cloudAt(200)->size(), 0u);
}

}  // namespace cg
