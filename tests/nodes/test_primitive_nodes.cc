// PrimitiveSim, WritePrimitive, WritePrimitivePly and PrimitiveLoad through the evaluator.

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <filesystem>
#include <string>
#include <tuple>
#include <vector>

#include "core/Evaluator.h"
#include "core/Graph.h"
#include "core/Registry.h"
#include "formats/PrimitiveFile.h"
#include "nodes/Builtin.h"
#include "nodes/data/CloudParticles.h"
#include "nodes/data/PrimitiveSet.h"
#include "support/TestUtil.h"

namespace cg {

namespace {

const char* kSim = R"({"cloudgraph": 1, "nodes": {
    "sim": {"type": "PrimitiveSim", "params": {"frames": 12, "width": 200, "height": 300,
            "spacing": 20, "sourceHeight": 60, "sourceRadius": 60, "sourceHumidity": 1.0}},
    "write": {"type": "WritePrimitive", "inputs": {"primitive": "sim.primitive"},
              "params": {"file": "p.cgp"}},
    "ply": {"type": "WritePrimitivePly", "inputs": {"primitive": "sim.primitive"},
            "params": {"file": "ply/frame.ply", "first": 9, "last": 11}}}})";

std::shared_ptr<const PrimitiveSetData> pullPrimitive(Registry& r, const Graph& g,
                                                      const std::string& node,
                                                      const std::filesystem::path& out)
{
    EvaluatorOptions o;
    o.outDir = out;
    Evaluator ev(r, o);
    ev.pull(g, "write", 0);
    ev.pull(g, "ply", 0);
    return std::dynamic_pointer_cast<const PrimitiveSetData>(ev.pull(g, node, 0)->at("primitive"));
}

}  // namespace

TEST(PrimitiveNodes, SimWriteLoadRoundTripAndThreadIndependence)
{
    Registry r;
    registerBuiltinNodes(r);
    test::TempDir out;
    const Graph g = parseGraph(kSim, "sim.json", r);
    const auto sim = pullPrimitive(r, g, "sim", out.path());
    ASSERT_TRUE(sim);
    EXPECT_EQ(sim->frames(), 12);
    EXPECT_TRUE(std::filesystem::exists(out / "ply/frame.0011.ply"));
    EXPECT_FALSE(std::filesystem::exists(out / "ply/frame.0008.ply"));

    const std::string file = (out / "p.cgp").string();
    const std::string load = R"({"cloudgraph": 1, "nodes": {"load": {"type": "PrimitiveLoad",
        "params": {"file": ")" +
                             file + R"("}}}})";
    const Graph lg = parseGraph(load, "load.json", r);
    Evaluator ev(r, {});
    const auto loaded =
        std::dynamic_pointer_cast<const PrimitiveSetData>(ev.pull(lg, "load", 0)->at("primitive"));
    ASSERT_TRUE(loaded);
    EXPECT_EQ(loaded->counts, sim->counts);
    EXPECT_EQ(loaded->positions, sim->positions);
    EXPECT_EQ(loaded->frameTime, sim->frameTime);

    // The key follows the file's content (the path is a parameter, so it is in the key too).
    const Key k1 = ev.key(lg, "load", 0);
    std::string bytes = test::readFile(out / "p.cgp");
    bytes[bytes.size() - 1] ^= 1;
    test::writeFile(out / "p.cgp", bytes);
    EXPECT_NE(ev.key(lg, "load", 0), k1);

    // Interpolation between frames.
    const int last = sim->frames() - 1;
    if (sim->count(last - 1) > 0) {
        float a[3], b[3], m[3];
        ASSERT_TRUE(sim->positionAt(last - 1, 0, a));
        ASSERT_TRUE(sim->positionAt(last, 0, b));
        ASSERT_TRUE(sim->positionAt(last - 0.5, 0, m));
        for (int k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(m[k], 0.5f * (a[k] + b[k]));
    }

    // One thread gives the same bits.
    test::TempDir out1;
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    const auto serial = pullPrimitive(r, g, "sim", out1.path());
    EXPECT_EQ(serial->counts, sim->counts);
    EXPECT_EQ(serial->positions, sim->positions);
}

TEST(PrimitiveNodes, PrimitiveFrameIsTheFrameScaledAndOffsetHeldAtTheEnds)
{
    Registry r;
    registerBuiltinNodes(r);
    // Three frames of 0, 2 and 3 particles.
    const std::vector<std::uint32_t> counts{0, 2, 3};
    const std::vector<float> positions{1,    2, 3,    4, 5,    6,                 // frame 1
                                       1.5f, 2, 3.5f, 4, 5.5f, 6, -7, 8, 9.25f};  // frame 2
    test::TempDir dir;
    formats::writePrimitiveFile(dir / "p.cgp", 2.0, counts, positions);
    const Graph g = parseGraph(R"({"cloudgraph": 1, "frames": {"start": 0, "end": 40}, "nodes": {
        "load": {"type": "PrimitiveLoad", "params": {"file": ")" +
                                   (dir / "p.cgp").string() + R"("}},
        "frame": {"type": "PrimitiveFrame", "inputs": {"primitive": "load.primitive"},
                  "params": {"scale": 2.5, "offset": [100, -50, 300]}}}})",
                               "frame.json", r);
    Evaluator ev(r, {});
    const double offset[3] = {100, -50, 300};
    // Evaluation frame 40 is past the primitive's last frame (2): the last frame holds.
    for (const auto& [evalFrame, s, first] :
         {std::tuple{1, 1, 0}, std::tuple{2, 2, 6}, std::tuple{40, 2, 6}}) {
        const auto cloud = std::dynamic_pointer_cast<const CloudParticlesData>(
            ev.pull(g, "frame", evalFrame)->at("particles"));
        ASSERT_TRUE(cloud);
        ASSERT_EQ(cloud->size(), counts[static_cast<std::size_t>(s)]);
        for (std::size_t q = 0; q < cloud->size(); ++q) {
            for (std::size_t a = 0; a < 3; ++a)
                EXPECT_EQ(cloud->positions()[3 * q + a],
                          static_cast<float>(offset[a]) +
                              2.5f * positions[static_cast<std::size_t>(first) + 3 * q + a]);
            EXPECT_EQ(cloud->levels()[q], 1);
            EXPECT_EQ(cloud->sources()[q], 0u);
        }
    }
    const auto empty = std::dynamic_pointer_cast<const CloudParticlesData>(
        ev.pull(g, "frame", 0)->at("particles"));
    EXPECT_EQ(empty->size(), 0u);
}

}  // namespace cg
