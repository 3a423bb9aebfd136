// Volume renderer: one 640 x 480 frame, fast mode and path traced, of a 5-million-particle
// cumulus voxelized by the Voxelizer's algorithm (10 m voxels), seen by the camera of
// graphs/cumulus_still.json (light maps included: they are rebuilt every frame).
// bench/run_render_bench.sh runs this and vdb_render on the same .vdb, same resolution and
// primary step, in the same script.
//
// Environment: CG_RENDER_BENCH_VDB=path writes the cloud there (for vdb_render) and exits.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <random>
#include <vector>

#include <openvdb/io/File.h>

#include "algo/render/integrators/RenderPathTrace.h"
#include "algo/render/integrators/RenderVolume.h"
#include "algo/render/scenes/SyntheticCumulus.h"
#include "algo/volume/Voxelize.h"
#include "util/FreedMemory.h"

namespace {

using cg::algo::RenderVec3;

constexpr std::size_t kParticles = 5000000;

/// kParticles cloud particles filling the blobs of graphs/cumulus_still.json's cumulus,
/// uniformly in each ball, as many per blob as its volume's share; flat base at 900 m.
const std::vector<float>& particles()
{
    static const std::vector<float> xyz = [] {
        cg::algo::SyntheticCumulusSettings s;
        s.seed = 3;
        s.baseHeight = 900.0;
        s.baseRadius = 700.0;
        s.towerHeight = 1.3;
        const auto blobs = cg::algo::cumulusBlobs(s);
        std::vector<double> cumulative;
        double total = 0.0;
        for (const auto& b : blobs) cumulative.push_back(total += b.radius * b.radius * b.radius);
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        std::vector<float> out;
        out.reserve(3 * kParticles);
        std::size_t blob = 0;
        for (std::size_t i = 0; i < kParticles; ++i) {
            const double at = total * (static_cast<double>(i) + 0.5) / kParticles;
            while (cumulative[blob] < at) ++blob;  // blob by blob, as the mapper emits
            const auto& b = blobs[blob];
            double p[3];
            do {
                for (double& c : p) c = u(rng);
            } while (p[0] * p[0] + p[1] * p[1] + p[2] * p[2] > 1.0);
            out.insert(out.end(), {static_cast<float>(b.x + b.radius * p[0]),
                                   static_cast<float>(b.y + b.radius * p[1]),
                                   static_cast<float>(std::max(b.z + b.radius * p[2], 900.0))});
        }
        return out;
    }();
    return xyz;
}

/// The Voxelizer's settings for this cloud: 10 m voxels (as the still), R = 1.5 voxels; about
/// 10 particles per voxel make the interior dense (clamped at 1), the edges soft.
cg::algo::VoxelizeSettings voxelizer()
{
    cg::algo::VoxelizeSettings v;
    v.voxelSize = 10.0;
    v.radius = 15.0;
    v.density = 0.06;
    return v;
}

const openvdb::FloatGrid& cloud()
{
    static const openvdb::FloatGrid::Ptr grid =
        cg::algo::voxelizeParticles(particles().data(), kParticles, voxelizer());
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

/// The reference path tracer on the same frame at one path a pixel: its time grows linearly
/// with the paths, so run_render_bench.sh scales it to the 2048 paths a pixel at which the
/// error table of docs/rendering.md calls the reference converged.
void BM_PathTraceCumulus640x480(benchmark::State& state)
{
    const openvdb::FloatGrid& grid = cloud();
    cg::algo::RenderSettings s = scene(0.5);
    s.pathTrace.samples = static_cast<int>(state.range(0));
    for (auto _ : state) benchmark::DoNotOptimize(cg::algo::renderPathTraced(grid, s).rgba.data());
    state.counters["paths"] = static_cast<double>(s.pathTrace.samples);
}
BENCHMARK(BM_PathTraceCumulus640x480)
    ->Arg(1)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// For reference: voxelizing the 5 million particles (the frame's other per-frame cost).
void BM_Voxelize5MParticles(benchmark::State& state)
{
    const auto& xyz = particles();
    for (auto _ : state)
        benchmark::DoNotOptimize(cg::algo::voxelizeParticles(xyz.data(), kParticles, voxelizer()));
}
BENCHMARK(BM_Voxelize5MParticles)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv)
{
    cg::util::keepFreedMemoryForReuse();  // as the CLI renders
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
