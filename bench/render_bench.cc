// Volume renderer: one 640 x 480 frame of the synthetic cumulus of graphs/cumulus_still.json
// (light maps included: they are rebuilt every frame). bench/run_render_bench.sh runs this
// and vdb_render on the same .vdb, same resolution and primary step, in the same script.
//
// Environment: CG_RENDER_BENCH_VDB=path writes the cloud there (for vdb_render) and exits.

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <iostream>

#include <openvdb/io/File.h>

#include "nodes/algo/RenderVolume.h"
#include "nodes/algo/SyntheticCumulus.h"

namespace {

using cg::algo::RenderVec3;

/// The cloud of graphs/cumulus_still.json.
const openvdb::FloatGrid& cloud()
{
    static const openvdb::FloatGrid::Ptr grid = [] {
        cg::algo::SyntheticCumulusSettings s;
        s.seed = 3;
        s.voxelSize = 10.0;
        s.baseHeight = 900.0;
        s.baseRadius = 700.0;
        s.towerHeight = 1.3;
        return cg::algo::rasterizeCumulus(cg::algo::cumulusBlobs(s), s);
    }();
    return *grid;
}

/// The camera and lights of graphs/cumulus_still.json.
cg::algo::RenderSettings scene(double step)
{
    cg::algo::RenderSettings s;
    s.camera.position = RenderVec3(400, -3800, 700);
    s.camera.lookAt = RenderVec3(0, 0, 1200);
    s.camera.fovDegrees = 40.0;
    s.camera.width = 640;
    s.camera.height = 480;
    s.sun.direction = RenderVec3(-1, -0.25, 0.65);
    s.sun.intensity = 20.0;
    s.march.step = step;
    return s;
}

void BM_RenderCumulus640x480(benchmark::State& state)
{
    const openvdb::FloatGrid& grid = cloud();
    const cg::algo::RenderSettings s = scene(static_cast<double>(state.range(0)) / 100.0);
    for (auto _ : state) benchmark::DoNotOptimize(cg::algo::renderFogVolume(grid, s).rgba.data());
    state.counters["activeVoxels"] = static_cast<double>(grid.activeVoxelCount());
}
// Argument: primary step in hundredths of a voxel (100 = vdb_render's default -step 1).
BENCHMARK(BM_RenderCumulus640x480)->Arg(100)->Arg(50)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SyntheticCumulus(benchmark::State& state)
{
    cg::algo::SyntheticCumulusSettings s;
    s.seed = 3;
    s.voxelSize = 10.0;
    s.baseHeight = 900.0;
    s.baseRadius = 700.0;
    s.towerHeight = 1.3;
    for (auto _ : state)
        benchmark::DoNotOptimize(cg::algo::rasterizeCumulus(cg::algo::cumulusBlobs(s), s));
}
BENCHMARK(BM_SyntheticCumulus)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv)
{
    openvdb::initialize();
    if (const char* path = std::getenv("CG_RENDER_BENCH_VDB")) {
        openvdb::io::File file(path);
        openvdb::GridCPtrVec grids{cloud().copyGrid()};
        file.write(grids);
        file.close();
        std::cout << "wrote " << path << " (" << cloud().activeVoxelCount() << " voxels)\n";
        return 0;
    }
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
