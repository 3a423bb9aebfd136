// ThermalIntegrator speed: particle-steps per second for 1 million particles, against a
// STREAM-like parallel copy of the same bytes measured in the same run.
//
//   bench/run_thermal_bench.sh build      (medians over repetitions, and the ratio)

#include <benchmark/benchmark.h>

#include <cstring>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "algo/atmosphere/Thermal.h"

namespace {

constexpr std::size_t kParticles = 1 << 20;
// One step reads z, vz, T and writes them anew: 6 floats per particle.
constexpr std::int64_t kBytesPerParticleStep = 6 * sizeof(float);

struct State {
    std::vector<float> z, vz, t;
    explicit State(std::size_t n) : z(n), vz(n), t(n)
    {
        for (std::size_t i = 0; i < n; ++i) {
            z[i] = static_cast<float>(i % 2000);
            vz[i] = static_cast<float>(i % 13);
            t[i] = 10.0f + static_cast<float>(i % 200) * 0.1f;
        }
    }
};

void BM_ThermalStep(benchmark::State& state)
{
    State a(kParticles), b(kParticles);
    cg::algo::ThermalSettings s;
    for (auto _ : state) {
        cg::algo::thermalStepParallel(s, {a.z.data(), a.vz.data(), a.t.data()},
                                      {b.z.data(), b.vz.data(), b.t.data()}, kParticles);
        std::swap(a, b);
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(kParticles));
    state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(kParticles) *
                            kBytesPerParticleStep);
}
BENCHMARK(BM_ThermalStep)->UseRealTime()->Unit(benchmark::kMillisecond);

/// The peer: copy the same three arrays, in parallel, as STREAM's copy kernel does.
void BM_StreamCopy(benchmark::State& state)
{
    State a(kParticles), b(kParticles);
    for (auto _ : state) {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, kParticles, 16384),
                          [&](const tbb::blocked_range<std::size_t>& r) {
                              const std::size_t bytes = r.size() * sizeof(float);
                              std::memcpy(b.z.data() + r.begin(), a.z.data() + r.begin(), bytes);
                              std::memcpy(b.vz.data() + r.begin(), a.vz.data() + r.begin(), bytes);
                              std::memcpy(b.t.data() + r.begin(), a.t.data() + r.begin(), bytes);
                          });
        std::swap(a, b);
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(kParticles));
    state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(kParticles) *
                            kBytesPerParticleStep);
}
BENCHMARK(BM_StreamCopy)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
