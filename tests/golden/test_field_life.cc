// A cumulus field that lives (issue 54), on the reduced cumulus_day of the golden harness: its
// clouds come and go and its cover steadies. Measured from above on the fog volume as
// bench/cloud_metrics does (algo/volume/CloudTracking.h). A golden statistic on a reduced
// graph, not a timed test.

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <map>

#include "algo/volume/CloudTracking.h"
#include "core/Evaluator.h"
#include "core/Graph.h"
#include "core/Registry.h"
#include "golden/GoldenRun.h"
#include "golden/GoldenSpecs.h"
#include "nodes/Builtin.h"
#include "nodes/data/FogVolume.h"

namespace cg::golden {

TEST(FieldLife, SmallCumulusDayCloudsComeAndGoWhileItsCoverSteadies)
{
    Registry registry;
    registerBuiltinNodes(registry);
    Graph g = loadGraph(graphsDir() / "cumulus_day.json", registry);
    findSpec("cumulus_day")->shrink(g);
    // The second half hour, every minute: the VDB writer's schedule decides the frames the
    // Voxelizer cooks (it is idle on the others).
    const int first = 450, every = 15, last = 900;
    g.setParam("vdb", "firstFrame", first, "test");
    g.setParam("vdb", "every", every, "test");
    const auto out = std::filesystem::temp_directory_path() / "cloudgraph_field_life";
    std::filesystem::remove_all(out);
    EvaluatorOptions options;
    options.outDir = out;
    Evaluator ev(registry, options);
    std::vector<algo::CoverFrame> frames;
    std::map<int, double> cover;
    double voxel = 0;
    const double size = 20000.0;  // the thermals' map, m
    ev.cookFrames(g, g.frames.start, last, {"vdb"}, [&](int f, const Evaluator::FrameOutputs& r) {
        if (f < first || (f - first) % every != 0) return;
        const auto v =
            std::dynamic_pointer_cast<const FogVolumeData>(r[g.indexOf("voxelize")]->at("volume"));
        const auto extinction = v->grid->getMetadata<openvdb::FloatMetadata>("extinction");
        voxel = v->grid->voxelSize()[0];
        frames.push_back(algo::coverOf(algo::topOpticalDepth(*v->grid, extinction->value())));
        cover[f] = algo::coverShare(frames.back(), voxel, 0, 0, size, size);
    });
    std::filesystem::remove_all(out);
    ASSERT_EQ(frames.size(), static_cast<std::size_t>((last - first) / every + 1));
    const algo::Turnover t = algo::trackTurnover(frames, 32, 4);
    const int threeQuarters = 675;  // 75% of the run, on the schedule
    std::printf(
        "small cumulus_day: %zu clouds at %d, %zu at %d; %zu gone, %zu new; cover "
        "%.1f%% at %d, %.1f%% at %d\n",
        t.firstClouds, first, t.lastClouds, last, t.gone, t.born, 100.0 * cover[threeQuarters],
        threeQuarters, 100.0 * cover[last], last);
    ASSERT_GE(t.firstClouds, 20u);
    ASSERT_GE(t.lastClouds, 20u);
    // Issue 54: at least a quarter of the middle frame's clouds gone by the end, a quarter of
    // the end's new since the middle.
    EXPECT_GE(4 * t.gone, t.firstClouds);
    EXPECT_GE(4 * t.born, t.lastClouds);
    // The cover steadies: the end's within 0.7-1.3 of the cover at 75% of the run. The small
    // primitive's clouds are smaller than the shipped one's, so the cover (6-8%) is under the
    // full graph's 27-39%: the bounds say the field neither empties nor fills up.
    EXPECT_GE(cover[last], 0.7 * cover[threeQuarters]);
    EXPECT_LE(cover[last], 1.3 * cover[threeQuarters]);
    for (const auto& [f, c] : cover) {
        EXPECT_GE(c, 0.03) << "frame " << f;
        EXPECT_LE(c, 0.40) << "frame " << f;
    }
}

}  // namespace cg::golden
