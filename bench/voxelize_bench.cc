// Voxelizer speed: 1 and 5 million cloud particles to a fog volume, against OpenVDB's own
// point rasterisation of the same particles in the same run:
//   - points::createPointDataGrid (build the VDB Points grid) + points::rasterizeTrilinear,
//   - points::rasterizeSpheres (narrow-band SDF from the same point grid),
//   - tools::ParticlesToLevelSet::rasterizeSpheres (narrow-band SDF from a particle list).
// The peers produce different fields (trilinear weights, level sets); they are the fastest
// OpenVDB paths from particles to a volume, compared here for time only.
//
//   build/bench/voxelize_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//
// Arguments: /particles in millions/radius in tenths of a voxel.

#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <random>
#include <vector>

#include <openvdb/openvdb.h>
#include <openvdb/points/PointAttribute.h>
#include <openvdb/points/PointConversion.h>
#include <openvdb/points/PointRasterizeSDF.h>
#include <openvdb/points/PointRasterizeTrilinear.h>
#include <openvdb/tools/ParticlesToLevelSet.h>

#include "algo/volume/Voxelize.h"

namespace {

constexpr double kVoxel = 4.0;     // m, the Voxelizer's default
constexpr float kDensity = 0.25f;  // the Voxelizer's default

/// A synthetic cumulus of `n` particles: 24 overlapping blobs (radius 80-220 m) over a
/// 1.2 km footprint, a flat base at 1 km and a dome rising to ~2 km; denser in blob cores.
/// Particles are emitted blob by blob, as the mapper emits them source by source.
const std::vector<float>& cumulus(std::size_t n)
{
    static std::map<std::size_t, std::vector<float>> cache;
    auto& xyz = cache[n];
    if (!xyz.empty()) return xyz;
    std::mt19937 rng(1234);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    struct Blob {
        double x, y, z, r;
    };
    std::vector<Blob> blobs;
    for (int b = 0; b < 24; ++b) {
        const double r = 80.0 + 140.0 * (0.5 + 0.5 * u(rng));
        const double x = 450.0 * u(rng), y = 450.0 * u(rng);
        const double dome = 1.0 - (x * x + y * y) / (650.0 * 650.0);
        blobs.push_back({x, y, 1000.0 + r + 700.0 * dome * (0.5 + 0.5 * u(rng)), r});
    }
    xyz.reserve(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
        const Blob& b = blobs[i * blobs.size() / n];
        double p[3];
        do {
            for (double& c : p) c = u(rng);
        } while (p[0] * p[0] + p[1] * p[1] + p[2] * p[2] > 1.0);
        const double s = b.r * std::cbrt(0.2 + 0.8 * (0.5 + 0.5 * u(rng)));  // denser core
        const double z = std::max(b.z + s * p[2], 1000.0);                   // flat base
        xyz.insert(xyz.end(), {static_cast<float>(b.x + s * p[0]),
                               static_cast<float>(b.y + s * p[1]), static_cast<float>(z)});
    }
    return xyz;
}

std::size_t particles(const benchmark::State& state)
{
    return static_cast<std::size_t>(state.range(0)) * 1000000;
}
double radius(const benchmark::State& state)
{
    return kVoxel * 0.1 * static_cast<double>(state.range(1));
}

std::vector<openvdb::Vec3s> asVec3s(const std::vector<float>& xyz)
{
    std::vector<openvdb::Vec3s> p(xyz.size() / 3);
    for (std::size_t i = 0; i < p.size(); ++i) p[i] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
    return p;
}

openvdb::points::PointDataGrid::Ptr pointGrid(const std::vector<openvdb::Vec3s>& p)
{
    const auto transform = openvdb::math::Transform::createLinearTransform(kVoxel);
    auto grid = openvdb::points::createPointDataGrid<openvdb::points::NullCodec,
                                                     openvdb::points::PointDataGrid>(p, *transform);
    openvdb::points::appendAttribute<float>(grid->tree(), "density", kDensity);
    return grid;
}

void voxelize(benchmark::State& state, cg::algo::VoxelKernel kernel)
{
    const auto& xyz = cumulus(particles(state));
    cg::algo::VoxelizeSettings s;
    s.kernel = kernel;
    s.voxelSize = kVoxel;
    s.radius = radius(state);
    s.density = kDensity;
    openvdb::FloatGrid::Ptr grid;
    for (auto _ : state) {
        grid = cg::algo::voxelizeParticles(xyz.data(), xyz.size() / 3, s);
        benchmark::DoNotOptimize(grid.get());
    }
    state.counters["active_voxels"] = static_cast<double>(grid->activeVoxelCount());
    state.counters["grid_MB"] = static_cast<double>(grid->memUsage()) / 1e6;
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(xyz.size() / 3));
}
void BM_Voxelize(benchmark::State& state) { voxelize(state, cg::algo::VoxelKernel::Smooth); }
/// The Gaussian kernel: trilinear deposit, then separable blur passes.
void BM_VoxelizeGaussian(benchmark::State& state)
{
    voxelize(state, cg::algo::VoxelKernel::Gaussian);
}

/// OpenVDB: build the point grid, then rasterise trilinearly (what a user of OpenVDB does).
void BM_OpenVdbTrilinear(benchmark::State& state)
{
    const auto p = asVec3s(cumulus(particles(state)));
    for (auto _ : state) {
        const auto points = pointGrid(p);
        auto tree = openvdb::points::rasterizeTrilinear<false, float>(points->tree(), "density");
        benchmark::DoNotOptimize(tree.get());
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(p.size()));
}

/// The two halves of the above, timed apart.
void BM_OpenVdbPointGridBuild(benchmark::State& state)
{
    const auto p = asVec3s(cumulus(particles(state)));
    for (auto _ : state) benchmark::DoNotOptimize(pointGrid(p).get());
}
void BM_OpenVdbTrilinearOnly(benchmark::State& state)
{
    const auto points = pointGrid(asVec3s(cumulus(particles(state))));
    for (auto _ : state) {
        auto tree = openvdb::points::rasterizeTrilinear<false, float>(points->tree(), "density");
        benchmark::DoNotOptimize(tree.get());
    }
}

/// points::rasterizeSpheres from a prebuilt point grid (narrow-band SDF, half width 3).
void BM_OpenVdbPointsRasterizeSpheres(benchmark::State& state)
{
    const auto points = pointGrid(asVec3s(cumulus(particles(state))));
    for (auto _ : state) {
        auto sdf = openvdb::points::rasterizeSpheres(*points, radius(state));
        benchmark::DoNotOptimize(sdf.get());
    }
}

/// tools::ParticlesToLevelSet::rasterizeSpheres straight from the particle array.
struct ParticleList {
    using PosType = openvdb::Vec3R;
    const std::vector<float>* xyz;
    double r;
    std::size_t size() const { return xyz->size() / 3; }
    void getPos(std::size_t n, openvdb::Vec3R& p) const
    {
        p = {(*xyz)[3 * n], (*xyz)[3 * n + 1], (*xyz)[3 * n + 2]};
    }
    void getPosRad(std::size_t n, openvdb::Vec3R& p, openvdb::Real& rad) const
    {
        getPos(n, p);
        rad = r;
    }
};
void BM_OpenVdbToolsRasterizeSpheres(benchmark::State& state)
{
    const ParticleList list{&cumulus(particles(state)), radius(state)};
    for (auto _ : state) {
        auto sdf = openvdb::createLevelSet<openvdb::FloatGrid>(kVoxel, 3.0);
        openvdb::tools::ParticlesToLevelSet<openvdb::FloatGrid> raster(*sdf);
        raster.setRmin(0.5);  // keep particles smaller than the default 1.5 voxels
        raster.rasterizeSpheres(list);
        raster.finalize();
        benchmark::DoNotOptimize(sdf.get());
    }
}

void args(benchmark::internal::Benchmark* b)
{
    for (const int m : {1, 5})
        for (const int r : {10, 20, 40}) b->Args({m, r});
    b->UseRealTime()->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();
}
void argsNoRadius(benchmark::internal::Benchmark* b)
{
    for (const int m : {1, 5}) b->Args({m, 0});
    b->UseRealTime()->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();
}

BENCHMARK(BM_Voxelize)->Apply(args);
BENCHMARK(BM_VoxelizeGaussian)->Apply(args);
BENCHMARK(BM_OpenVdbTrilinear)->Apply(argsNoRadius);
BENCHMARK(BM_OpenVdbPointGridBuild)->Apply(argsNoRadius);
BENCHMARK(BM_OpenVdbTrilinearOnly)->Apply(argsNoRadius);
BENCHMARK(BM_OpenVdbPointsRasterizeSpheres)->Apply(args);
BENCHMARK(BM_OpenVdbToolsRasterizeSpheres)->Apply(args);

}  // namespace

int main(int argc, char** argv)
{
    openvdb::initialize();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
