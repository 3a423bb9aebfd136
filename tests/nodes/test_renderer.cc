// Renderer and SyntheticCumulus through the evaluator: sizes, determinism, load-time refusals.

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <string>

#include "algo/render/integrators/RenderVolume.h"
#include "algo/render/scenes/SyntheticCumulus.h"
#include "core/CoreData.h"
#include "core/Error.h"
#include "core/Evaluator.h"
#include "core/Graph.h"
#include "core/Registry.h"
#include "nodes/data/DataTypes.h"
#include "nodes/data/FogVolume.h"
#include "nodes/data/Image.h"
#include "nodes/render/RenderNodes.h"
#include "support/FixtureNodes.h"

namespace cg {

namespace {

class RendererNodeTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        registerCoreDataTypes(registry);
        registerNodeDataTypes(registry);
        registerFixtureNodes(registry);
        registerSyntheticCumulusNode(registry);
        registerRendererNode(registry);
    }

    Graph parse(const std::string& text, LoadOptions limits = {})
    {
        return parseGraph(text, "test.json", registry, limits);
    }

    template <class T>
    std::shared_ptr<const T> pull(const Graph& g, const std::string& node, const std::string& port)
    {
        Evaluator ev(registry, {});
        return std::dynamic_pointer_cast<const T>(ev.pull(g, node, 0)->at(port));
    }

    Registry registry;
};

const char* kSmallScene = R"({"cloudgraph": 1, "nodes": {
    "cloud": {"type": "SyntheticCumulus", "params": {"voxelSize": 40, "levels": 3}},
    "render": {"type": "Renderer", "inputs": {"volume": "cloud.volume"},
               "params": {"width": 48, "height": 32, "cameraPosition": [0, -5000, 900],
                          "cameraLookAt": [0, 0, 1300]}}}})";

}  // namespace

TEST_F(RendererNodeTest, RendersTheRequestedSizeInLinearRadiance)
{
    const auto img = pull<ImageData>(parse(kSmallScene), "render", "image");
    ASSERT_TRUE(img);
    EXPECT_EQ(img->width, 48);
    EXPECT_EQ(img->height, 32);
    ASSERT_EQ(img->rgba.size(), std::size_t(48 * 32 * 4));
    float maxAlpha = 0.0f;
    for (std::size_t i = 0; i < img->rgba.size(); ++i) {
        ASSERT_TRUE(std::isfinite(img->rgba[i])) << i;
        ASSERT_GE(img->rgba[i], 0.0f) << i;
        if (i % 4 == 3) maxAlpha = std::max(maxAlpha, img->rgba[i]);
    }
    EXPECT_GT(maxAlpha, 0.99f);  // the cloud is in view and opaque somewhere
}

TEST_F(RendererNodeTest, SyntheticCumulusIsAFogVolumeWithAFlatBase)
{
    const auto fog = pull<FogVolumeData>(parse(kSmallScene), "cloud", "volume");
    ASSERT_TRUE(fog);
    const openvdb::FloatGrid& grid = *fog->grid;
    EXPECT_EQ(grid.getName(), "density");
    EXPECT_EQ(grid.getGridClass(), openvdb::GRID_FOG_VOLUME);
    EXPECT_DOUBLE_EQ(grid.voxelSize().x(), 40.0);
    ASSERT_GT(grid.activeVoxelCount(), 1000u);
    const algo::SyntheticCumulusSettings def;
    for (auto it = grid.cbeginValueOn(); it; ++it) {
        ASSERT_GT(*it, 0.0f);
        ASSERT_LE(*it, 1.0f);
        // Nothing below the base (one voxel of smooth cut above it).
        ASSERT_GE(grid.indexToWorld(it.getCoord()).z(), def.baseHeight - 0.5 * 40.0);
    }
}

TEST_F(RendererNodeTest, SyntheticCumulusIsIdenticalForOneAndTwoThreads)
{
    algo::SyntheticCumulusSettings s;
    s.voxelSize = 40.0;
    const auto blobs = algo::cumulusBlobs(s);
    EXPECT_GE(blobs.size(), 200u);  // a few hundred blobs at the default 4 levels
    openvdb::FloatGrid::Ptr one, two;
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
        one = algo::rasterizeCumulus(blobs, s);
    }
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
        two = algo::rasterizeCumulus(blobs, s);
    }
    ASSERT_EQ(one->activeVoxelCount(), two->activeVoxelCount());
    auto acc = two->getConstAccessor();
    for (auto it = one->cbeginValueOn(); it; ++it) {
        ASSERT_TRUE(acc.isValueOn(it.getCoord()));
        ASSERT_EQ(acc.getValue(it.getCoord()), *it);
    }
}

TEST_F(RendererNodeTest, AbsurdResolutionIsRefusedAtLoad)
{
    // Out of the declared range.
    EXPECT_THROW(parse(R"({"cloudgraph": 1, "nodes": {
        "fog": {"type": "TestFogSource"},
        "render": {"type": "Renderer", "inputs": {"volume": "fog.volume"},
                   "params": {"width": 100000}}}})"),
                 InputError);
    EXPECT_THROW(parse(R"({"cloudgraph": 1, "nodes": {
        "fog": {"type": "TestFogSource"},
        "render": {"type": "Renderer", "inputs": {"volume": "fog.volume"},
                   "params": {"height": 0}}}})"),
                 InputError);
    // In range, but over the allocation limit: 8000 x 8000 x 28 bytes (RGBA and background)
    // > 512 MiB.
    LoadOptions limits;
    limits.allocationLimitBytes = 512ull << 20;
    try {
        parse(R"({"cloudgraph": 1, "nodes": {
            "fog": {"type": "TestFogSource"},
            "render": {"type": "Renderer", "inputs": {"volume": "fog.volume"},
                       "params": {"width": 8000, "height": 8000}}}})",
              limits);
        FAIL() << "expected an InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("width"), std::string::npos) << e.what();
    }
    // A camera that cannot be built.
    EXPECT_THROW(parse(R"({"cloudgraph": 1, "nodes": {
        "fog": {"type": "TestFogSource"},
        "render": {"type": "Renderer", "inputs": {"volume": "fog.volume"},
                   "params": {"cameraPosition": [1, 2, 3], "cameraLookAt": [1, 2, 3]}}}})"),
                 InputError);
    EXPECT_THROW(parse(R"({"cloudgraph": 1, "nodes": {
        "cloud": {"type": "SyntheticCumulus", "params": {"voxelSize": 1, "baseRadius": 20000}}}})",
                       limits),
                 InputError);
}

}  // namespace cg
