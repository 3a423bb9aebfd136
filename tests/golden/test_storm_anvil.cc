// A cumulonimbus's anvil (issue 54), on the reduced figure8_cumulonimbus_sounding of the golden
// harness at its last frame: the outflow's ice is one sheet, not the mapper's row of puffs,
// and far thinner per gram than the liquid tower. Statistics of shape on a reduced graph, each
// with its counterpart that fails (no spread, no ice).

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <string>

#include "algo/atmosphere/Parcel.h"
#include "algo/volume/CloudRegions.h"
#include "core/Evaluator.h"
#include "core/Graph.h"
#include "core/Registry.h"
#include "golden/GoldenRun.h"
#include "golden/GoldenSpecs.h"
#include "nodes/Builtin.h"
#include "nodes/data/AtmosphereData.h"
#include "nodes/data/FogVolume.h"

namespace cg::golden {

namespace {

constexpr int kFrame = 300;

struct Storm {
    openvdb::FloatGrid::ConstPtr grid;
    double outflow = 0;  ///< m above the ground where the spreading is full
};

/// The small storm's volume at its last frame with `param` set to `value` on the Voxelizer.
Storm storm(const std::string& param, const nlohmann::json& value)
{
    Registry registry;
    registerBuiltinNodes(registry);
    Graph g = loadGraph(graphsDir() / "figure8_cumulonimbus_sounding.json", registry);
    findSpec("figure8_cumulonimbus_sounding")->shrink(g);
    if (!param.empty()) g.setParam("voxelize", param, value, "test");
    Evaluator ev(registry, {});
    const auto volume = std::dynamic_pointer_cast<const FogVolumeData>(
        ev.pull(g, "voxelize", kFrame)->at("volume"));
    const auto air = std::dynamic_pointer_cast<const AtmosphereData>(
        ev.pull(g, "atmosphere", kFrame)->at("atmosphere"));
    const algo::EnvironmentProfile profile = environmentProfileOf(air->atmosphere);
    const double el = algo::liftParcel(profile, profile.groundHeight()).elM;
    // The Voxelizer's anvilDepth (2 km) under the EL, full a kilometre higher.
    return {volume->grid, el - profile.groundHeight() - 1000.0};
}

/// Seen from above, the outflow layers' clouds (tau >= 0.1): the largest one's share of them.
double largestSheetShare(const Storm& s, std::size_t* clouds)
{
    const openvdb::FloatGrid& grid = *s.grid;
    const double voxel = grid.voxelSize()[0];
    const double perUnit = grid.metaValue<float>("extinction");
    const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
    algo::Mask2D mask;
    mask.width = box.dim().x();
    mask.height = box.dim().y();
    std::vector<double> tau(static_cast<std::size_t>(mask.width) * mask.height, 0.0);
    for (auto it = grid.cbeginValueOn(); it; ++it) {
        const openvdb::Coord c = it.getCoord();
        if (c.z() * voxel < s.outflow) continue;
        tau[static_cast<std::size_t>(c.y() - box.min().y()) * mask.width +
            (c.x() - box.min().x())] += *it * perUnit * voxel;
    }
    mask.set.resize(tau.size());
    std::transform(tau.begin(), tau.end(), mask.set.begin(),
                   [](double t) { return static_cast<std::uint8_t>(t >= 0.1); });
    const algo::Regions regions = algo::labelRegions(mask);
    *clouds = regions.area.size();
    if (regions.area.empty()) return 0.0;
    const double total = std::accumulate(regions.area.begin(), regions.area.end(), 0.0);
    return *std::max_element(regions.area.begin(), regions.area.end()) / total;
}

/// The largest extinction (1/m) in the outflow layers over the largest below them.
double outflowOverTower(const Storm& s)
{
    const double voxel = s.grid->voxelSize()[0];
    float outflow = 0.0f, tower = 0.0f;
    for (auto it = s.grid->cbeginValueOn(); it; ++it) {
        float& peak = it.getCoord().z() * voxel >= s.outflow ? outflow : tower;
        peak = std::max(peak, *it);
    }
    return outflow / tower;
}

}  // namespace

TEST(StormAnvil, TheOutflowIsOneSheetOfIceOverALiquidTower)
{
    const Storm shipped = storm("", nullptr);
    const Storm puffs = storm("iceSpread", 0.0);
    const Storm liquid = storm("ice", false);
    std::size_t sheetClouds = 0, puffClouds = 0, liquidClouds = 0;
    const double sheet = largestSheetShare(shipped, &sheetClouds);
    const double unspread = largestSheetShare(puffs, &puffClouds);
    largestSheetShare(liquid, &liquidClouds);
    std::printf("outflow from above: %zu clouds, the largest %.3f of them (%zu, %.3f unspread)\n",
                sheetClouds, sheet, puffClouds, unspread);
    std::printf("outflow / tower extinction: %.4f with ice, %.4f liquid\n",
                outflowOverTower(shipped), outflowOverTower(liquid));
    // The small storm's two cells spread into one sheet with at most a scrap beside it
    // (2 clouds, the largest 0.86 of the area); unspread, 15 puffs, the largest 0.28.
    EXPECT_LE(sheetClouds, 3u);
    EXPECT_GT(sheet, 0.75) << "the outflow is one sheet";
    EXPECT_GT(puffClouds, 5u);
    EXPECT_LT(unspread, 0.5) << "without the spread it is the copies' puffs";
    // Ice of a twentieth of the condensate, crystals 30 um: its extinction is a small share of
    // the liquid tower's (0.028); left liquid it would be comparable (0.93).
    EXPECT_LT(outflowOverTower(shipped), 0.1);
    EXPECT_GT(outflowOverTower(liquid), 0.3);
}

}  // namespace cg::golden
