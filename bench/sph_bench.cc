// SPH speed (algo/fluid/Sph*): neighbour search for 16k and 1M particles against a plain
// reference measured in the same run, and the time of one solver sub-step from 16k to 1M
// fluid particles (the basis of "hybrid vs simulating every particle physically").
//
//   build/bench/sph_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "algo/fluid/SphGrid.h"
#include "algo/fluid/SphSolver.h"

namespace {

constexpr double kRadius = 2.0;  // the solver's support H = 2 dx, with dx = 1

/// A lattice of n^3 points of spacing 1, jittered by up to 0.2: a fluid in motion.
std::vector<double> jitteredLattice(int n)
{
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-0.2, 0.2);
    std::vector<double> x;
    x.reserve(3 * static_cast<std::size_t>(n) * n * n);
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                x.push_back(i + 0.5 + u(rng));
                x.push_back(j + 0.5 + u(rng));
                x.push_back(k + 0.5 + u(rng));
            }
    return x;
}

int sideFor(std::int64_t count) { return static_cast<int>(std::lround(std::cbrt(count))); }

/// Ours: SphGrid's counting sort, then every point's neighbours gathered in parallel.
void BM_NeighbourSearch(benchmark::State& state)
{
    const int n = sideFor(state.range(0));
    const std::vector<double> x = jitteredLattice(n);
    const std::size_t count = x.size() / 3;
    const double lo[3] = {0, 0, 0}, hi[3] = {double(n), double(n), double(n)};
    cg::algo::SphGrid grid(lo, hi, kRadius);
    std::uint64_t pairs = 0;
    for (auto _ : state) {
        grid.build(x.data(), count);
        pairs = tbb::parallel_reduce(
            tbb::blocked_range<std::size_t>(0, count, 1024), std::uint64_t{0},
            [&](const tbb::blocked_range<std::size_t>& r, std::uint64_t acc) {
                for (std::size_t i = r.begin(); i != r.end(); ++i)
                    grid.forEachNeighbour(&x[3 * i], kRadius, [&](std::uint32_t) { ++acc; });
                return acc;
            },
            [](std::uint64_t a, std::uint64_t b) { return a + b; });
        benchmark::DoNotOptimize(pairs);
    }
    state.counters["particles"] = static_cast<double>(count);
    state.counters["neighbours"] = static_cast<double>(pairs) / static_cast<double>(count);
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(count));
}

/// The plain reference: (cell, index) pairs sorted with std::sort, a table of cell starts,
/// then the neighbours of every point gathered from its 27 cells, on one thread.
void BM_NeighbourSearchReference(benchmark::State& state)
{
    const int n = sideFor(state.range(0));
    const std::vector<double> x = jitteredLattice(n);
    const std::size_t count = x.size() / 3;
    const int dims = static_cast<int>(std::ceil(n / kRadius));
    auto cellOf = [&](const double* p, int c[3]) {
        for (int a = 0; a < 3; ++a)
            c[a] = std::clamp(static_cast<int>(p[a] / kRadius), 0, dims - 1);
    };
    std::vector<std::pair<std::uint32_t, std::uint32_t>> keyed(count);
    std::vector<std::uint32_t> start(static_cast<std::size_t>(dims) * dims * dims + 1);
    std::uint64_t pairs = 0;
    for (auto _ : state) {
        for (std::size_t i = 0; i < count; ++i) {
            int c[3];
            cellOf(&x[3 * i], c);
            keyed[i] = {static_cast<std::uint32_t>((c[2] * dims + c[1]) * dims + c[0]),
                        static_cast<std::uint32_t>(i)};
        }
        std::sort(keyed.begin(), keyed.end());
        std::fill(start.begin(), start.end(), 0u);
        for (const auto& k : keyed) ++start[k.first + 1];
        for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
        pairs = 0;
        for (std::size_t i = 0; i < count; ++i) {
            const double* p = &x[3 * i];
            int c[3];
            cellOf(p, c);
            for (int dz = -1; dz <= 1; ++dz)
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int cx = c[0] + dx, cy = c[1] + dy, cz = c[2] + dz;
                        if (cx < 0 || cy < 0 || cz < 0 || cx >= dims || cy >= dims || cz >= dims)
                            continue;
                        const std::size_t cell =
                            (static_cast<std::size_t>(cz) * dims + cy) * dims + cx;
                        for (std::uint32_t k = start[cell]; k < start[cell + 1]; ++k) {
                            const double* q = &x[3 * std::size_t{keyed[k].second}];
                            const double ex = q[0] - p[0], ey = q[1] - p[1], ez = q[2] - p[2];
                            if (ex * ex + ey * ey + ez * ez < kRadius * kRadius) ++pairs;
                        }
                    }
        }
        benchmark::DoNotOptimize(pairs);
    }
    state.counters["particles"] = static_cast<double>(count);
    state.counters["neighbours"] = static_cast<double>(pairs) / static_cast<double>(count);
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(count));
}

/// One sub-step (neighbours, density, forces, pressure solve, integration) of a cube of air
/// with a warm blob rising in it, dx = 20 m, dt = 1 s; after a few steps, so it moves.
void BM_SolverStep(benchmark::State& state)
{
    const int n = sideFor(state.range(0));
    cg::algo::SphSettings s;
    const double lo[3] = {0, 0, 0}, hi[3] = {20.0 * n, 20.0 * n, 20.0 * n};
    cg::algo::SphSolver solver(s, lo, hi);
    const std::vector<double>& x = solver.positions();
    const double c = 10.0 * n, r = 4.0 * n;
    for (std::size_t i = 0; i < solver.size(); ++i) {
        const double dx = x[3 * i] - c, dy = x[3 * i + 1] - c, dz = x[3 * i + 2] - 0.6 * c;
        if (dx * dx + dy * dy + dz * dz < r * r) solver.temperatures()[i] += 2.0;
    }
    for (int k = 0; k < (n < 100 ? 3 : 1); ++k) solver.step(1.0);
    long long iterations = 0;
    for (auto _ : state) {
        solver.step(1.0);
        iterations += solver.lastStats().iterations;
    }
    state.counters["particles"] = static_cast<double>(solver.size());
    state.counters["cg_iterations"] =
        static_cast<double>(iterations) / static_cast<double>(state.iterations());
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(solver.size()));
}

}  // namespace

BENCHMARK(BM_NeighbourSearch)
    ->Arg(16000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_NeighbourSearchReference)
    ->Arg(16000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_SolverStep)
    ->Arg(16000)
    ->Arg(64000)
    ->Arg(256000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_SolverStep)->Arg(1000000)->Iterations(2)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
