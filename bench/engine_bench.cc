// Engine overhead benchmarks: key hashing, cache hits, cooks, and the disk cache against a
// plain file write/read of the same bytes (the peer measured in the same run).
//
//   build/bench/engine_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include <fcntl.h>
#include <unistd.h>

#include <fstream>
#include <random>

#include <nlohmann/json.hpp>

#include "core/CoreData.h"
#include "core/DiskCache.h"
#include "core/Evaluator.h"
#include "core/Graph.h"
#include "nodes/Builtin.h"

namespace cg {

namespace {

const Registry& registry()
{
    static Registry* r = [] {
        auto* reg = new Registry;
        registerBuiltinNodes(*reg);
        return reg;
    }();
    return *r;
}

/// RandomField (count values) followed by `length` Scale nodes.
Graph chain(int length, int count)
{
    nlohmann::json nodes;
    nodes["n0"] = {{"type", "RandomField"}, {"params", {{"width", count}, {"height", 1}}}};
    for (int i = 1; i <= length; ++i)
        nodes["n" + std::to_string(i)] = {
            {"type", "Scale"},
            {"params", {{"factor", 1.0 + i * 1e-3}}},
            {"inputs", {{"values", "n" + std::to_string(i - 1) + ".values"}}}};
    return parseGraph(nlohmann::json{{"cloudgraph", 1}, {"nodes", nodes}}.dump(), "bench",
                      registry());
}

std::filesystem::path scratchDir()
{
    auto p =
        std::filesystem::temp_directory_path() / ("cloudgraph-bench-" + std::to_string(::getpid()));
    std::filesystem::create_directories(p);
    return p;
}

}  // namespace

/// Hashing the keys of a 100-node chain, per node.
static void BM_KeysPerNode(benchmark::State& state)
{
    const Graph g = chain(100, 16);
    Evaluator ev(registry(), {});
    for (auto _ : state) benchmark::DoNotOptimize(ev.key(g, "n100", 0));
    state.SetItemsProcessed(state.iterations() * 101);
}
BENCHMARK(BM_KeysPerNode);

/// Pulling a 100-node chain whose values are all in the memory cache, per node.
static void BM_MemoryHitPerNode(benchmark::State& state)
{
    const Graph g = chain(100, 16);
    Evaluator ev(registry(), {});
    ev.pull(g, "n100", 0);
    for (auto _ : state) {
        ev.report().clear();
        benchmark::DoNotOptimize(ev.pull(g, "n100", 0));
    }
    state.SetItemsProcessed(state.iterations() * 101);
}
BENCHMARK(BM_MemoryHitPerNode);

/// Cooking a 100-node chain of Scale nodes on `range(0)` floats, per node.
static void BM_CookPerNode(benchmark::State& state)
{
    const Graph g = chain(100, static_cast<int>(state.range(0)));
    for (auto _ : state) {
        Evaluator ev(registry(), {});
        benchmark::DoNotOptimize(ev.pull(g, "n100", 0));
    }
    state.SetItemsProcessed(state.iterations() * 101);
}
BENCHMARK(BM_CookPerNode)->Arg(16)->Arg(1 << 16);

/// The same Scale arithmetic as a plain loop that, like a cache, keeps every intermediate
/// array: the peer for BM_CookPerNode.
static void BM_PlainLoopPerNode(benchmark::State& state)
{
    const auto n = static_cast<std::size_t>(state.range(0));
    for (auto _ : state) {
        std::vector<std::vector<float>> kept;
        kept.emplace_back(n, 0.5f);
        for (int i = 1; i <= 100; ++i) {
            std::vector<float> next(n);
            const std::vector<float>& v = kept.back();
            for (std::size_t k = 0; k < n; ++k)
                next[k] = static_cast<float>(v[k] * (1.0 + i * 1e-3));
            kept.push_back(std::move(next));
        }
        benchmark::DoNotOptimize(kept.back().data());
    }
    state.SetItemsProcessed(state.iterations() * 101);
}
BENCHMARK(BM_PlainLoopPerNode)->Arg(16)->Arg(1 << 16);

/// Storing and loading a 16 MiB FloatArray through the disk cache (with checksums, fsync).
static void BM_DiskCacheRoundTrip16MiB(benchmark::State& state)
{
    const auto dir = scratchDir();
    DiskCache cache(dir / "cache");
    std::vector<float> values(4 << 20);
    std::mt19937 rng(1);
    for (float& v : values) v = static_cast<float>(rng());
    OutputMap out{{"values", std::make_shared<FloatArrayData>(values)}};
    Key key{1, 0};
    for (auto _ : state) {
        ++key.lo;
        cache.store(key, out);
        benchmark::DoNotOptimize(cache.load(key, registry()));
        std::filesystem::remove(cache.entryPath(key));
    }
    state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(values.size() * 4));
    std::filesystem::remove_all(dir);
}
BENCHMARK(BM_DiskCacheRoundTrip16MiB)->Unit(benchmark::kMillisecond)->UseRealTime();

/// The peer: write (with fsync) and read back the same bytes as a plain file.
static void BM_PlainFileRoundTrip16MiB(benchmark::State& state)
{
    const auto dir = scratchDir();
    std::vector<float> values(4 << 20);
    std::mt19937 rng(1);
    for (float& v : values) v = static_cast<float>(rng());
    const auto path = dir / "plain.bin";
    for (auto _ : state) {
        {
            std::ofstream f(path, std::ios::binary);
            f.write(reinterpret_cast<const char*>(values.data()),
                    static_cast<std::streamsize>(values.size() * 4));
        }
        const int fd = ::open(path.c_str(), O_RDONLY);  // fsync, as the disk cache does
        ::fsync(fd);
        ::close(fd);
        std::vector<float> back(values.size());
        std::ifstream in(path, std::ios::binary);
        in.read(reinterpret_cast<char*>(back.data()),
                static_cast<std::streamsize>(back.size() * 4));
        benchmark::DoNotOptimize(back.data());
        std::filesystem::remove(path);
    }
    state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(values.size() * 4));
    std::filesystem::remove_all(dir);
}
BENCHMARK(BM_PlainFileRoundTrip16MiB)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace cg

BENCHMARK_MAIN();
