// The Voxelizer node through the evaluator: same grid as the algorithm, metadata, bad input.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <string>

#include <openvdb/tools/Count.h>

#include "algo/volume/Voxelize.h"
#include "core/Error.h"
#include "core/Evaluator.h"
#include "core/Graph.h"
#include "core/Registry.h"
#include "nodes/data/CloudParticles.h"
#include "nodes/data/DataTypes.h"
#include "nodes/data/FogVolume.h"
#include "nodes/volume/VolumeNodes.h"
#include "support/FixtureNodes.h"
#include "support/GridChecksum.h"

namespace cg {

namespace {

std::shared_ptr<const FogVolumeData> volumeAt(Evaluator& ev, const Graph& g, int frame)
{
    return std::dynamic_pointer_cast<const FogVolumeData>(ev.pull(g, "vox", frame)->at("volume"));
}

class VoxelizerNodeTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        registerCoreDataTypes(registry);
        registerNodeDataTypes(registry);
        registerFixtureNodes(registry);
        registerVoxelizerNode(registry);
    }

    Graph parse(const std::string& text) { return parseGraph(text, "test.json", registry); }

    Registry registry;
};

const char* kGraph = R"({"cloudgraph": 1, "nodes": {
    "cloud": {"type": "TestCloudSource", "params": {"radius": 30, "spacing": 2}},
    "vox": {"type": "Voxelizer", "inputs": {"particles": "cloud.particles"},
            "params": {"voxelSize": 1.5, "radius": 4.0, "density": 0.4, "detailAmplitude": 0,
                       "kernel": "smooth"}}}})";

}  // namespace

TEST_F(VoxelizerNodeTest, OutputsTheAlgorithmsGridWithMetadata)
{
    const Graph g = parse(kGraph);
    Evaluator ev(registry, {});
    const auto particles = std::dynamic_pointer_cast<const CloudParticlesData>(
        ev.pull(g, "cloud", 7)->at("particles"));
    const auto volume = volumeAt(ev, g, 7);
    ASSERT_TRUE(particles);
    ASSERT_TRUE(volume);
    const openvdb::FloatGrid& grid = *volume->grid;
    EXPECT_EQ(grid.getName(), "density");
    EXPECT_EQ(grid.getGridClass(), openvdb::GRID_FOG_VOLUME);
    EXPECT_EQ(grid.voxelSize(), openvdb::Vec3d(1.5));
    EXPECT_EQ(grid.metaValue<openvdb::Int32>("frame"), 7);
    EXPECT_EQ(grid.metaValue<std::string>("units"), "metres");
    EXPECT_EQ(grid.metaValue<double>("voxel_size_m"), 1.5);
    EXPECT_EQ(grid.metaValue<double>("particle_radius_m"), 4.0);
    EXPECT_EQ(grid.metaValue<std::string>("kernel"), "smooth");
    EXPECT_EQ(grid.metaValue<openvdb::Int64>("particle_count"),
              static_cast<openvdb::Int64>(particles->size()));

    algo::VoxelizeSettings s;
    s.voxelSize = 1.5;
    s.radius = 4.0;
    s.density = 0.4;
    const auto expected =
        algo::voxelizeParticles(particles->positions().data(), particles->size(), s);
    ASSERT_EQ(grid.activeVoxelCount(), expected->activeVoxelCount());
    auto acc = grid.getConstAccessor();
    for (auto it = expected->tree().cbeginValueOn(); it; ++it)
        ASSERT_EQ(acc.getValue(it.getCoord()), *it);
    const auto range = openvdb::tools::minMax(grid.tree());
    const float lo = range.min(), hi = range.max();
    EXPECT_GT(lo, 0.0f);
    EXPECT_LE(hi, 1.0f);
}

// The grid the Voxelizer made before surface detail existed (version 1), pinned by its checksum:
// with the detail off it must come out bit for bit the same.
TEST_F(VoxelizerNodeTest, DetailOffReproducesTheVersion1GridBitForBit)
{
    Graph g = parse(kGraph);
    Evaluator ev(registry, {});
    const auto volume = volumeAt(ev, g, 3);
    EXPECT_EQ(volume->grid->activeVoxelCount(), 45817u);
    EXPECT_EQ(test::gridChecksum(*volume->grid), 2565534684775939884ull);
}

TEST_F(VoxelizerNodeTest, FrameOnlyChangesTheMetadata)
{
    const Graph g = parse(kGraph);
    Evaluator ev(registry, {});
    const auto a = volumeAt(ev, g, 1);
    const auto b = volumeAt(ev, g, 2);
    EXPECT_EQ(a->grid->metaValue<openvdb::Int32>("frame"), 1);
    EXPECT_EQ(b->grid->metaValue<openvdb::Int32>("frame"), 2);
    EXPECT_EQ(a->grid->activeVoxelCount(), b->grid->activeVoxelCount());
}

TEST_F(VoxelizerNodeTest, FilterOptionSmoothsTheVolume)
{
    Graph g = parse(kGraph);
    Evaluator ev(registry, {});
    const auto plain = volumeAt(ev, g, 0);
    g.setParam("vox", "filter", "gaussian");
    g.setParam("vox", "filterIterations", 2);
    const auto smooth = volumeAt(ev, g, 0);
    EXPECT_EQ(plain->grid->activeVoxelCount(), smooth->grid->activeVoxelCount());
    auto acc = smooth->grid->getConstAccessor();
    std::size_t changed = 0;
    for (auto it = plain->grid->tree().cbeginValueOn(); it; ++it)
        changed += acc.getValue(it.getCoord()) != *it;
    EXPECT_GT(changed, 0u);
}

TEST_F(VoxelizerNodeTest, RadiusBeyond32VoxelsIsRefusedAtLoad)
{
    EXPECT_THROW(parse(R"({"cloudgraph": 1, "nodes": {
        "cloud": {"type": "TestCloudSource"},
        "vox": {"type": "Voxelizer", "inputs": {"particles": "cloud.particles"},
                "params": {"voxelSize": 0.1, "radius": 4.0}}}})"),
                 InputError);
}

TEST_F(VoxelizerNodeTest, AWarpReachingBeyond64VoxelsIsRefusedAtLoadNamingIt)
{
    // 4 octaves at roughness 0.6: reach 2.176 x amplitude; 64 voxels of 1 m hold 29 m, not 30.
    const auto graph = [](double amplitude) {
        return R"({"cloudgraph": 1, "nodes": {
            "cloud": {"type": "TestCloudSource"},
            "vox": {"type": "Voxelizer", "inputs": {"particles": "cloud.particles"},
                    "params": {"voxelSize": 1, "radius": 4.0, "warpAmplitude": )" +
               std::to_string(amplitude) + "}}}}";
    };
    EXPECT_NO_THROW(parse(graph(29.0)));
    try {
        parse(graph(30.0));
        ADD_FAILURE() << "a warp reaching 65 voxels was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("warpAmplitude"), std::string::npos) << e.what();
    }
}

TEST_F(VoxelizerNodeTest, AllIceNoColderThanFirstIceIsRefusedAtLoadNamingIt)
{
    const auto graph = [](const char* end) {
        return std::string(R"({"cloudgraph": 1, "nodes": {
            "cloud": {"type": "TestCloudSource"},
            "vox": {"type": "Voxelizer", "inputs": {"particles": "cloud.particles"},
                    "params": {"voxelSize": 1, "radius": 4.0, "glaciationStart": -20,
                               "glaciationEnd": )") +
               end + "}}}}";
    };
    EXPECT_NO_THROW(parse(graph("-21")));
    try {
        parse(graph("-20"));
        ADD_FAILURE() << "all ice at the first ice's temperature was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("vox/params/glaciationEnd"), std::string::npos)
            << e.what();
    }
}

TEST_F(VoxelizerNodeTest, WaterAndFlatBasesWithoutTheirInputsAreRefusedNamingTheInput)
{
    for (const char* params : {R"("optics": "water")", R"("flatBase": true)"}) {
        const Graph g = parse(std::string(R"({"cloudgraph": 1, "nodes": {
            "cloud": {"type": "TestCloudSource", "params": {"radius": 30, "spacing": 2}},
            "vox": {"type": "Voxelizer", "inputs": {"particles": "cloud.particles"},
                    "params": {"voxelSize": 1.5, "radius": 4.0, )") +
                              params + "}}}}");
        Evaluator ev(registry, {});
        try {
            volumeAt(ev, g, 0);
            ADD_FAILURE() << params << " cooked without its condensation input";
        } catch (const CookError& e) {
            EXPECT_NE(std::string(e.what()).find("vox/inputs/condensation"), std::string::npos)
                << e.what();
        }
    }
}

}  // namespace cg
