// "bypass": true on a node: a writer writes nothing, a node whose outputs are of its first
// input's type passes that input through, anything else is refused at load naming the node;
// the switch enters the key, survives a save, and `--set node.bypass=true` sets it.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/CoreData.h"
#include "core/Error.h"
#include "core/Evaluator.h"
#include "core/Graph.h"
#include "core/Registry.h"
#include "nodes/Builtin.h"
#include "nodes/data/Map2D.h"
#include "support/TestUtil.h"

namespace cg {

namespace {

class BypassTest : public ::testing::Test {
protected:
    void SetUp() override { registerBuiltinNodes(registry); }

    /// A noise map, a MapMath that inverts it and a WriteMap of the result; `invert` and
    /// `write` hold extra node fields.
    Graph graph(const std::string& invert = "", const std::string& write = "")
    {
        return parseGraph(R"({"cloudgraph": 1, "frames": {"start": 0, "end": 2}, "nodes": {
            "noise": {"type": "NoiseMap", "params": {"width": 8, "height": 8}},
            "invert": {"type": "MapMath", "inputs": {"a": "noise.map"},
                       "params": {"op": "invert"})" +
                              invert + R"(},
            "write": {"type": "WriteMap", "inputs": {"map": "invert.map"},
                      "params": {"file": "m.####.pfm"})" +
                              write + "}}}",
                          "g.json", registry);
    }

    std::string refusal(const std::string& text)
    {
        try {
            parseGraph(text, "g.json", registry);
        } catch (const InputError& e) {
            return e.what();
        }
        return "";
    }

    test::TempDir out;
    Registry registry;
};

}  // namespace

TEST_F(BypassTest, ABypassedWriterWritesNothingAndANodePassesItsInputThrough)
{
    const Graph g = graph(R"(, "bypass": true)", R"(, "bypass": true)");
    EvaluatorOptions options;
    options.outDir = out.path();
    Evaluator ev(registry, options);
    ev.cookFrames(g, 0, 2);
    EXPECT_TRUE(std::filesystem::is_empty(out.path()));
    const auto files =
        std::dynamic_pointer_cast<const TextData>(ev.pull(g, "write", 1)->at("files"));
    EXPECT_EQ(files->value, "");
    // The bypassed MapMath hands on the noise itself, not its inverse.
    EXPECT_EQ(ev.pull(g, "invert", 0)->at("map"), ev.pull(g, "noise", 0)->at("map"));

    const Graph on = graph();
    Evaluator fresh(registry, options);
    fresh.cookFrames(on, 0, 0);
    EXPECT_TRUE(std::filesystem::exists(out / "m.0000.pfm"));
    EXPECT_NE(fresh.key(on, "invert", 0), ev.key(g, "invert", 0));
}

TEST_F(BypassTest, AMeaninglessBypassIsRefusedNamingTheNode)
{
    // NoiseMap has no input to pass through.
    const std::string source = refusal(R"({"cloudgraph": 1, "nodes": {
        "noise": {"type": "NoiseMap", "bypass": true}}})");
    EXPECT_NE(source.find("/nodes/noise/bypass"), std::string::npos) << source;
    EXPECT_NE(source.find("no input to pass through"), std::string::npos) << source;
    // A Voxelizer makes a volume from particles: nothing to stand in for it.
    const std::string voxelizer = refusal(R"({"cloudgraph": 1, "nodes": {
        "cloud": {"type": "PrimitiveFrame", "inputs": {"primitive": "sim.primitive"}},
        "sim": {"type": "PrimitiveSim"},
        "vox": {"type": "Voxelizer", "inputs": {"particles": "cloud.particles"}, "bypass": true}}})");
    EXPECT_NE(voxelizer.find("makes FogVolume ('volume') from CloudParticles"), std::string::npos)
        << voxelizer;
    EXPECT_NE(refusal(R"({"cloudgraph": 1, "nodes": {
        "noise": {"type": "NoiseMap", "bypass": "yes"}}})")
                  .find("must be true or false"),
              std::string::npos);
}

TEST_F(BypassTest, SetTurnsItOnAndASaveKeepsIt)
{
    Graph g = graph();
    applySetOverride(g, "write.bypass=true");
    EXPECT_TRUE(g.find("write")->bypass);
    EXPECT_EQ(graphToJson(g)["nodes"]["write"]["bypass"], true);
    EXPECT_FALSE(graphToJson(g)["nodes"]["invert"].contains("bypass"));
    const Graph again = parseGraph(graphToJson(g).dump(), "again.json", registry);
    EXPECT_TRUE(again.find("write")->bypass);
    applySetOverride(g, "write.bypass=false");
    EXPECT_FALSE(g.find("write")->bypass);
    try {
        applySetOverride(g, "noise.bypass=true");
        ADD_FAILURE() << "a bypass of a source was accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(e.where(), "--set noise.bypass");
    }
    // A bypassed writer may keep a name without ####: it writes nothing.
    const std::string oneName = R"({"cloudgraph": 1, "frames": {"start": 0, "end": 2}, "nodes": {
        "noise": {"type": "NoiseMap"},
        "write": {"type": "WriteMap", "inputs": {"map": "noise.map"},
                  "params": {"file": "m.pfm"}, "bypass": true}}})";
    EXPECT_NO_THROW(parseGraph(oneName, "g.json", registry));
}

}  // namespace cg
