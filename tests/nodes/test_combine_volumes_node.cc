// CombineVolumes: the per-voxel maximum or clamped sum of two fog volumes, checked voxel by
// voxel over the union of both; mismatched grids are refused.

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>

#include "core/Error.h"
#include "core/Evaluator.h"
#include "core/Graph.h"
#include "core/Registry.h"
#include "nodes/Builtin.h"
#include "nodes/data/FogVolume.h"
#include "support/FixtureNodes.h"

namespace cg {

namespace {

std::string graph(const std::string& mode, double voxelB)
{
    return R"({"cloudgraph": 1, "nodes": {
        "a": {"type": "TestCloudSource", "params": {"radius": 20, "spacing": 2}},
        "b": {"type": "TestCloudSource", "params": {"radius": 12, "spacing": 1.5}},
        "va": {"type": "Voxelizer", "inputs": {"particles": "a.particles"},
               "params": {"voxelSize": 1.5, "radius": 4.0, "density": 0.3}},
        "vb": {"type": "Voxelizer", "inputs": {"particles": "b.particles"},
               "params": {"voxelSize": )" +
           std::to_string(voxelB) + R"(, "radius": 3.0, "density": 0.2}},
        "mix": {"type": "CombineVolumes", "inputs": {"a": "va.volume", "b": "vb.volume"},
                "params": {"mode": ")" +
           mode + R"("}}}})";
}

std::shared_ptr<const FogVolumeData> volume(Evaluator& ev, const Graph& g, const std::string& node)
{
    return std::dynamic_pointer_cast<const FogVolumeData>(ev.pull(g, node, 0)->at("volume"));
}

}  // namespace

TEST(CombineVolumes, MaxAndClampedSumVoxelByVoxel)
{
    Registry r;
    registerBuiltinNodes(r);
    registerFixtureNodes(r);
    for (const std::string mode : {"max", "sum"}) {
        const Graph g = parseGraph(graph(mode, 1.5), "mix.json", r);
        Evaluator ev(r, {});
        const auto a = volume(ev, g, "va"), b = volume(ev, g, "vb"), mix = volume(ev, g, "mix");
        ASSERT_TRUE(a && b && mix);
        EXPECT_EQ(mix->grid->getName(), "density");
        EXPECT_EQ(mix->grid->getGridClass(), openvdb::GRID_FOG_VOLUME);
        auto ea = a->grid->getConstAccessor(), eb = b->grid->getConstAccessor();
        auto em = mix->grid->getConstAccessor();
        std::size_t checked = 0, summedOverOne = 0;
        for (const auto* source : {&a, &b})
            for (auto it = (*source)->grid->cbeginValueOn(); it; ++it) {
                const openvdb::Coord c = it.getCoord();
                const float va = ea.getValue(c), vb = eb.getValue(c);
                const float expected = mode == "max" ? std::max(va, vb) : std::min(1.0f, va + vb);
                ASSERT_EQ(em.getValue(c), expected) << mode << " at " << c;
                ASSERT_TRUE(em.isValueOn(c));
                summedOverOne += va + vb > 1.0f;
                ++checked;
            }
        EXPECT_GT(checked, 1000u);
        if (mode == "sum") {
            EXPECT_GT(summedOverOne, 0u);  // the clamp was exercised
        }
        // No voxel beyond the union.
        EXPECT_LE(mix->grid->activeVoxelCount(),
                  a->grid->activeVoxelCount() + b->grid->activeVoxelCount());
        // The cached inputs are untouched.
        EXPECT_EQ(volume(ev, g, "va")->grid->activeVoxelCount(), a->grid->activeVoxelCount());
    }
}

TEST(CombineVolumes, DifferentVoxelSizesAreRefusedNamingTheNode)
{
    Registry r;
    registerBuiltinNodes(r);
    registerFixtureNodes(r);
    const Graph g = parseGraph(graph("max", 2.0), "mix.json", r);
    Evaluator ev(r, {});
    try {
        ev.pull(g, "mix", 0);
        FAIL() << "volumes of 1.5 m and 2 m voxels were combined";
    } catch (const CookError& e) {
        EXPECT_TRUE(e.inputFault());
        const std::string what = e.what();
        EXPECT_NE(what.find("mix"), std::string::npos) << what;
        EXPECT_NE(what.find("voxelSize"), std::string::npos) << what;
    }
}

}  // namespace cg
