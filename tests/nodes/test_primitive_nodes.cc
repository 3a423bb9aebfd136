// PrimitiveSim, WritePrimitive, WritePrimitivePly and PrimitiveLoad through the evaluator.

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <filesystem>
#include <string>

#include "core/Evaluator.h"
#include "core/Graph.h"
#include "core/Registry.h"
#include "nodes/Builtin.h"
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

}  // namespace cg
