// NoiseMap and WriteMap through the evaluator.

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "algo/atmosphere/NoiseMap.h"
#include "core/CoreData.h"
#include "core/Error.h"
#include "core/Evaluator.h"
#include "core/Graph.h"
#include "core/Registry.h"
#include "formats/MapImage.h"
#include "nodes/atmosphere/AtmosphereNodes.h"
#include "nodes/data/DataTypes.h"
#include "nodes/data/Map2D.h"
#include "nodes/io/IoNodes.h"
#include "support/TestUtil.h"

namespace cg {

namespace {

class NoiseMapNodeTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        registerCoreDataTypes(registry);
        registerNodeDataTypes(registry);
        registerNoiseMapNode(registry);
        registerWriteMapNode(registry);
    }

    Graph parse(const std::string& text) { return parseGraph(text, "test.json", registry); }

    std::shared_ptr<const Map2DData> pullMap(const Graph& g, EvaluatorOptions options = {})
    {
        Evaluator ev(registry, std::move(options));
        return std::dynamic_pointer_cast<const Map2DData>(ev.pull(g, "noise", 0)->at("map"));
    }

    Registry registry;
};

const char* kNoise = R"({"cloudgraph": 1, "nodes": {
    "noise": {"type": "NoiseMap",
              "params": {"width": 150, "height": 100, "beta": 3.3, "seed": 7, "cellSize": 25}}}})";

}  // namespace

TEST_F(NoiseMapNodeTest, ProducesTheAlgorithmsMap)
{
    const auto map = pullMap(parse(kNoise));
    ASSERT_TRUE(map);
    EXPECT_EQ(map->nx, 150);
    EXPECT_EQ(map->ny, 100);
    EXPECT_EQ(map->cellSize, 25.0);
    algo::NoiseMapSettings s;
    s.nx = 150;
    s.ny = 100;
    s.beta = 3.3;
    s.seed = 7;
    EXPECT_EQ(map->values, algo::noiseMap(s));
}

TEST_F(NoiseMapNodeTest, DefaultsAreA64x64MapOf50mCells)
{
    const auto map = pullMap(parse(R"({"cloudgraph": 1, "nodes": {
        "noise": {"type": "NoiseMap"}}})"));
    ASSERT_TRUE(map);
    EXPECT_EQ(map->nx, 64);
    EXPECT_EQ(map->ny, 64);
    EXPECT_EQ(map->cellSize, 50.0);
}

TEST_F(NoiseMapNodeTest, IdenticalForOneAndTwoThreads)
{
    const Graph g = parse(R"({"cloudgraph": 1, "nodes": {
        "noise": {"type": "NoiseMap",
                  "params": {"width": 300, "height": 125, "centreBias": 0.5, "seed": 3}}}})");
    std::shared_ptr<const Map2DData> one, two;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = pullMap(g);
    }
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        two = pullMap(g);
    }
    ASSERT_TRUE(one && two);
    ASSERT_EQ(one->values.size(), two->values.size());
    EXPECT_EQ(
        std::memcmp(one->values.data(), two->values.data(), one->values.size() * sizeof(float)), 0);
}

TEST_F(NoiseMapNodeTest, FrameIndependentSoOneKeyPerAnimation)
{
    const Graph g = parse(kNoise);
    Evaluator ev(registry, {});
    EXPECT_EQ(ev.key(g, "noise", 0), ev.key(g, "noise", 17));
}

TEST_F(NoiseMapNodeTest, AbsurdSizeIsRefusedAtLoad)
{
    try {
        parse(R"({"cloudgraph": 1, "nodes": {
            "noise": {"type": "NoiseMap", "params": {"width": 65536, "height": 65536}}}})");
        FAIL() << "expected an InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("/nodes/noise"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("width"), std::string::npos) << e.what();
    }
    EXPECT_THROW(parse(R"({"cloudgraph": 1, "nodes": {
            "noise": {"type": "NoiseMap", "params": {"width": 70000}}}})"),
                 InputError);
}

TEST_F(NoiseMapNodeTest, AMapThatCannotFitInAQuarterOfTheMachineIsRefusedAtLoad)
{
    // The audit's 24000^2 map (16 GB of FFT arrays) on a 24 GiB machine, whose limit is 6 GiB.
    LoadOptions machineOf24GiB;
    machineOf24GiB.allocationLimitBytes = util::nodeAllocationLimitBytes();
    EXPECT_LE(machineOf24GiB.allocationLimitBytes, std::uint64_t{16} << 30);
    machineOf24GiB.allocationLimitBytes = 6ull << 30;
    EXPECT_THROW(parseGraph(R"({"cloudgraph": 1, "nodes": {
            "noise": {"type": "NoiseMap", "params": {"width": 24000, "height": 24000}}}})",
                            "t.json", registry, machineOf24GiB),
                 InputError);
    EXPECT_NO_THROW(parseGraph(R"({"cloudgraph": 1, "nodes": {
            "noise": {"type": "NoiseMap", "params": {"width": 4096, "height": 4096}}}})",
                               "t.json", registry, machineOf24GiB));
}

TEST_F(NoiseMapNodeTest, WriteMapWritesPfmAndPngPerFrame)
{
    test::TempDir out;
    const Graph g = parse(R"({"cloudgraph": 1, "frames": {"start": 3, "end": 4}, "nodes": {
        "noise": {"type": "NoiseMap", "params": {"width": 40, "height": 30, "seed": 2}},
        "write": {"type": "WriteMap", "params": {"file": "maps/density.####.pfm"},
                  "inputs": {"map": "noise.map"}}}})");
    EvaluatorOptions options;
    options.outDir = out.path();
    Evaluator ev(registry, options);
    ev.cookFrames(g, 3, 4);

    const auto map = std::dynamic_pointer_cast<const Map2DData>(ev.pull(g, "noise", 3)->at("map"));
    ASSERT_TRUE(map);
    for (const char* frame : {"0003", "0004"}) {
        const auto pfm = out / (std::string("maps/density.") + frame + ".pfm");
        const auto png = out / (std::string("maps/density.") + frame + ".png");
        ASSERT_TRUE(std::filesystem::exists(pfm)) << pfm;
        ASSERT_TRUE(std::filesystem::exists(png)) << png;
        const formats::MapImage a = formats::readPfm(pfm.string());
        EXPECT_EQ(a.nx, 40);
        EXPECT_EQ(a.ny, 30);
        EXPECT_EQ(a.values, map->values);
        const formats::MapImage b = formats::readPng16(png.string());
        ASSERT_EQ(b.values.size(), map->values.size());
        for (std::size_t i = 0; i < b.values.size(); ++i)
            ASSERT_LE(std::abs(b.values[i] - map->values[i]), 1.0f / 65535.0f) << i;
    }
    // Nothing else: no temp files left behind.
    std::size_t count = 0;
    for (const auto& e : std::filesystem::recursive_directory_iterator(out.path()))
        if (e.is_regular_file()) ++count;
    EXPECT_EQ(count, 4u);

    const auto files =
        std::dynamic_pointer_cast<const TextData>(ev.pull(g, "write", 4)->at("files"));
    ASSERT_TRUE(files);
    EXPECT_EQ(files->value, (out / "maps/density.0004.pfm").string() + "\n" +
                                (out / "maps/density.0004.png").string());
}

TEST_F(NoiseMapNodeTest, WriteMapHonoursEvery)
{
    test::TempDir out;
    const Graph g = parse(R"({"cloudgraph": 1, "frames": {"start": 1, "end": 4}, "nodes": {
        "noise": {"type": "NoiseMap", "params": {"width": 8, "height": 8}},
        "write": {"type": "WriteMap", "params": {"file": "m.####.pfm", "every": 2},
                  "inputs": {"map": "noise.map"}}}})");
    EvaluatorOptions options;
    options.outDir = out.path();
    Evaluator ev(registry, options);
    ev.cookFrames(g, 1, 4);
    EXPECT_TRUE(std::filesystem::exists(out / "m.0001.pfm"));
    EXPECT_TRUE(std::filesystem::exists(out / "m.0003.png"));
    EXPECT_FALSE(std::filesystem::exists(out / "m.0002.pfm"));
    EXPECT_FALSE(std::filesystem::exists(out / "m.0004.png"));
}

TEST_F(NoiseMapNodeTest, WriteMapPreviewNameNeverCollides)
{
    test::TempDir out;
    const Graph g = parse(R"({"cloudgraph": 1, "frames": {"start": 1, "end": 1}, "nodes": {
        "noise": {"type": "NoiseMap", "params": {"width": 8, "height": 8}},
        "write": {"type": "WriteMap", "params": {"file": "m.png"},
                  "inputs": {"map": "noise.map"}}}})");
    EvaluatorOptions options;
    options.outDir = out.path();
    Evaluator ev(registry, options);
    ev.cookFrames(g, 1, 1);
    EXPECT_EQ(formats::readPfm((out / "m.png").string()).nx, 8);
    EXPECT_EQ(formats::readPng16((out / "m.png.png").string()).nx, 8);
}

}  // namespace cg
