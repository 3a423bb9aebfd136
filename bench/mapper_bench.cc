// PrimitiveMapper / GenerateCloud speed and memory (Sec. 5.2, Eq. 10-16; issue 5).
//
//   bench/run_mapper_bench.sh build-bench        (medians over repetitions, ratios, bytes)
//   build-bench/bench/mapper_bench --scene-info  (the synthetic Figure 5 scene, level by level)
//
// A synthetic but realistic Figure 5-scale scene is built here, without the engine:
//   - a primitive set of 154 frames whose N_f(s) grows to 16,401 fluid particles (the paper's
//     Figure 2 primitive: 16,401 particles, 154 steps), each particle rising and spreading;
//   - a 300 x 125 density map (the paper's Figure 5 resolution), 20 m cells;
//   - 4,000 condensation particles that condense between frames 30 and 280 and keep rising;
//   - the real selection (algo::stepSources) over 612 frames, 4 levels, which reaches about
//     4.5 million cloud particles at the last frame (the paper's Figure 5: 4,534,381).
//
// Only the library's generators are measured (algo/mapping/Mapping.h):
//   BM_Figure5/0   the whole 612-frame run: selection + positions of every frame from
//                  algo::forEachCloudChunk (4,096-particle chunks in a reused per-thread 48 KB
//                  buffer), counted, as a streaming consumer (voxelizer, PLY writer) takes them;
//                  peak memory beyond the primitive set measured by a counting operator new and
//                  by getrusage (ru_maxrss).
//   BM_Figure5/1   the same with algo::generateCloudParticles (the whole frame in fresh arrays:
//                  positions, level, source id = 17 bytes a particle), as GenerateCloud does.
//   BM_Generate*   the last frame (about 4.5 M particles) alone: particles per second, and bytes
//                  per second at 12 bytes (xyz float32) a particle, against a STREAM-like
//                  parallel write and copy of the same 54 MB (larger than the 32 MB L3) in the
//                  same run. BM_GenerateFrameBuffer: forEachCloudChunk writing straight into
//                  one reused frame array (CloudChunkOptions::positionsOut).
//
// forEachCloudChunk's chunks (positions, levels, sources; and its frame-array mode) are
// checked bit for bit against generateCloudParticles (every 97th frame and the last) before
// the single-frame benchmarks run; the program aborts on a difference. BM_Figure5/0 checks its
// count against Eq. 13. ru_maxrss is a process-wide high-water mark: rss_B_per_particle means
// something only for the first run in a process (run_mapper_bench.sh starts one process per Figure
// 5 run).

#include <benchmark/benchmark.h>

#include <malloc.h>
#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "algo/CounterRandom.h"
#include "algo/mapping/Mapping.h"

// ---------------------------------------------------------------------------------------------
// Counting allocator: live heap bytes (malloc_usable_size) and their high-water mark, so the
// Figure 5 run can report the peak memory it allocated beyond what existed before it started.

namespace {
std::atomic<std::int64_t> g_live{0};
std::atomic<std::int64_t> g_peak{0};

void* countedAlloc(std::size_t n)
{
    void* p = std::malloc(n == 0 ? 1 : n);
    if (p == nullptr) throw std::bad_alloc();
    const auto size = static_cast<std::int64_t>(malloc_usable_size(p));
    const std::int64_t now = g_live.fetch_add(size, std::memory_order_relaxed) + size;
    std::int64_t peak = g_peak.load(std::memory_order_relaxed);
    while (now > peak && !g_peak.compare_exchange_weak(peak, now, std::memory_order_relaxed)) {
    }
    return p;
}

void countedFree(void* p) noexcept
{
    if (p == nullptr) return;
    g_live.fetch_sub(static_cast<std::int64_t>(malloc_usable_size(p)), std::memory_order_relaxed);
    std::free(p);
}
}  // namespace

void* operator new(std::size_t n) { return countedAlloc(n); }
void* operator new[](std::size_t n) { return countedAlloc(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept
{
    try {
        return countedAlloc(n);
    } catch (...) {
        return nullptr;
    }
}
void* operator new[](std::size_t n, const std::nothrow_t& t) noexcept { return operator new(n, t); }
void operator delete(void* p) noexcept { countedFree(p); }
void operator delete[](void* p) noexcept { countedFree(p); }
void operator delete(void* p, std::size_t) noexcept { countedFree(p); }
void operator delete[](void* p, std::size_t) noexcept { countedFree(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { countedFree(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { countedFree(p); }

namespace {

using namespace cg::algo;

constexpr int kPrimitiveFrames = 154;
constexpr std::uint32_t kPrimitiveParticles = 16401;
constexpr int kFrames = 612;
constexpr std::size_t kCondensation = 4000;
constexpr int kMapX = 300, kMapY = 125;
constexpr double kCell = 20.0;  // metres: a 6 km x 2.5 km map
constexpr std::int64_t kBytesPerParticle = 3 * sizeof(float);

float hashUnit(std::uint64_t stream, std::uint64_t i)
{
    return static_cast<float>(counterUniform(20260611, stream, i));
}

/// The inputs of the run, built before any measurement: what the mapper reads but does not own.
struct Scene {
    std::vector<std::uint32_t> counts;
    std::vector<std::vector<float>> frames;
    std::vector<const float*> framePointers;
    std::vector<float> map;
    std::vector<float> homeX, homeY;  // condensation particles' ground positions
    std::vector<std::int32_t> condenseAt;
    MappingSettings settings;
    std::size_t primitiveBytes = 0;

    Scene()
    {
        // Primitive: N_f(s) grows as s^1.3 to 16,401; particle i spreads from the centre and rises.
        for (int s = 0; s < kPrimitiveFrames; ++s) {
            const double u = static_cast<double>(s + 1) / kPrimitiveFrames;
            counts.push_back(std::max<std::uint32_t>(
                1,
                static_cast<std::uint32_t>(std::lround(kPrimitiveParticles * std::pow(u, 1.3)))));
        }
        counts.back() = kPrimitiveParticles;
        for (int s = 0; s < kPrimitiveFrames; ++s) {
            std::vector<float> f(3 * static_cast<std::size_t>(counts[static_cast<std::size_t>(s)]));
            for (std::uint32_t i = 0; i < counts[static_cast<std::size_t>(s)]; ++i) {
                const float a = 6.2831853f * hashUnit(1, i), c = hashUnit(2, i), r = hashUnit(3, i);
                const float radius = (2.0f + 0.25f * static_cast<float>(s)) * (0.3f + 0.7f * r);
                const float sinT = std::sqrt(1.0f - c * c);
                f[3 * i] = radius * sinT * std::cos(a);
                f[3 * i + 1] = radius * sinT * std::sin(a);
                f[3 * i + 2] = radius * c + 0.4f * static_cast<float>(s);
            }
            primitiveBytes += f.size() * sizeof(float);
            frames.push_back(std::move(f));
        }
        for (const auto& f : frames) framePointers.push_back(f.data());
        // Density map: smooth, dense in the middle (the paper's Figure 6 pattern), in [0, 1].
        for (int iy = 0; iy < kMapY; ++iy)
            for (int ix = 0; ix < kMapX; ++ix) {
                const double dx = (ix - kMapX / 2.0) / (kMapX / 2.0),
                             dy = (iy - kMapY / 2.0) / (kMapY / 2.0);
                const double v = 0.65 * std::exp(-2.0 * (dx * dx + dy * dy)) +
                                 0.25 * (0.5 + 0.5 * std::sin(0.11 * ix) * std::cos(0.17 * iy)) +
                                 0.1 * hashUnit(4, static_cast<std::uint64_t>(iy * kMapX + ix));
                map.push_back(static_cast<float>(std::clamp(v, 0.0, 1.0)));
            }
        // Condensation particles: spread over the map, condensing at frames 30..279.
        for (std::size_t k = 0; k < kCondensation; ++k) {
            homeX.push_back(static_cast<float>(kMapX * kCell) * (0.1f + 0.8f * hashUnit(5, k)));
            homeY.push_back(static_cast<float>(kMapY * kCell) * (0.1f + 0.8f * hashUnit(6, k)));
            condenseAt.push_back(30 + static_cast<std::int32_t>(450.0f * hashUnit(7, k)));
        }
        settings.maxLevel = 4;
        settings.selectionRatio = {0.03, 4.8e-5, 4.2e-5, 4.6e-5};
        settings.levelDelay = 50;
        settings.windowLength = {450, 350};
        settings.seed = 5;
    }

    PrimitiveView primitive() const
    {
        PrimitiveView p;
        p.counts = counts.data();
        p.frames = framePointers.data();
        p.frameCount = kPrimitiveFrames;
        p.frameTime = 1.0;
        return p;
    }
    MapView mapView() const { return {map.data(), kMapX, kMapY, kCell}; }
};

const Scene& scene()
{
    static const Scene s;
    return s;
}

/// The condensation particles at frame t (what Condensation hands the mapper): rising at
/// 2 m a frame towards the condensation level at 1 km, then 1 m a frame above it.
struct Condensation {
    std::vector<float> x, y, z;
    std::vector<std::int32_t> condensed;
    std::vector<float> condensedZ;
    Condensation()
        : x(kCondensation),
          y(kCondensation),
          z(kCondensation),
          condensed(kCondensation),
          condensedZ(kCondensation)
    {
    }
    CondensationView at(const Scene& sc, int t)
    {
        for (std::size_t k = 0; k < kCondensation; ++k) {
            const int c = sc.condenseAt[k];
            x[k] = sc.homeX[k];
            y[k] = sc.homeY[k];
            z[k] = t < c ? 1000.0f * static_cast<float>(t) / static_cast<float>(c)
                         : 1000.0f + static_cast<float>(t - c);
            condensed[k] = t >= c ? c : -1;
            condensedZ[k] = t >= c ? 1000.0f : NAN;
        }
        return {x.data(), y.data(), z.data(), condensed.data(), condensedZ.data(), kCondensation};
    }
};

int firstCondensation(const Scene& sc, int t)
{
    int first = -1;
    for (auto c : sc.condenseAt)
        if (c <= t && (first < 0 || c < first)) first = c;
    return first;
}

/// The source table of every frame's selection, and the condensation at the last frame.
struct Selection {
    SourceTable last;
    double seconds = 0;
};

const Selection& finalSelection()
{
    static const Selection sel = [] {
        const Scene& sc = scene();
        Condensation cond;
        Selection out;
        const auto start = std::chrono::steady_clock::now();
        for (int t = 0; t < kFrames; ++t)
            out.last = stepSources(out.last, t, firstCondensation(sc, t), cond.at(sc, t),
                                   sc.mapView(), sc.primitive(), sc.settings);
        out.seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return out;
    }();
    return sel;
}

std::uint64_t total(const std::vector<std::uint64_t>& v)
{
    std::uint64_t t = 0;
    for (auto x : v) t += x;
    return t;
}

/// The streamed chunks (positions, levels, sources) and the frame-array mode of
/// algo::forEachCloudChunk against algo::generateCloudParticles, bit for bit, with every
/// particle delivered exactly once.
void verifyBitIdentical()
{
    const Scene& sc = scene();
    Condensation cond;
    SourceTable table;
    for (int t = 0; t < kFrames; ++t) {
        const CondensationView c = cond.at(sc, t);
        table = stepSources(table, t, firstCondensation(sc, t), c, sc.mapView(), sc.primitive(),
                            sc.settings);
        if (t % 97 != 0 && t != kFrames - 1) continue;
        const auto ref = generateCloudParticles(table, t, c, sc.primitive(), sc.settings);
        const std::size_t n = ref.levels.size();
        std::vector<float> streamed(3 * n, -1.0f), direct(3 * n, -2.0f);
        std::vector<std::uint8_t> levels(n, 0);
        std::vector<std::uint32_t> sources(n, 0xffffffffu);
        std::atomic<std::uint64_t> delivered{0};
        CloudChunkOptions withAll;
        withAll.levels = withAll.sources = true;
        const std::uint64_t total = forEachCloudChunk(
            table, t, c, sc.primitive(), sc.settings,
            [&](const CloudChunk& k) {
                std::memcpy(&streamed[3 * k.first], k.positions, 3 * k.count * sizeof(float));
                std::memcpy(&levels[k.first], k.levels, k.count);
                std::memcpy(&sources[k.first], k.sources, k.count * sizeof(std::uint32_t));
                delivered.fetch_add(k.count, std::memory_order_relaxed);
            },
            withAll);
        CloudChunkOptions into;
        into.positionsOut = direct.data();
        forEachCloudChunk(table, t, c, sc.primitive(), sc.settings, {}, into);
        if (total != n || delivered.load() != n ||
            std::memcmp(streamed.data(), ref.positions.data(), streamed.size() * sizeof(float)) !=
                0 ||
            std::memcmp(direct.data(), ref.positions.data(), direct.size() * sizeof(float)) != 0 ||
            std::memcmp(levels.data(), ref.levels.data(), n) != 0 ||
            std::memcmp(sources.data(), ref.sources.data(), n * sizeof(std::uint32_t)) != 0) {
            std::fprintf(
                stderr,
                "mapper_bench: forEachCloudChunk differs from generateCloudParticles at frame %d\n",
                t);
            std::abort();
        }
    }
}

long maxRssBytes()
{
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return u.ru_maxrss * 1024L;
}

/// The whole Figure 5 run. Arg 0: streamed into per-thread chunks; 1: generateCloudParticles.
void BM_Figure5(benchmark::State& state)
{
    const Scene& sc = scene();
    const bool library = state.range(0) == 1;
    double select = 0, generate = 0, bytesPerParticle = 0, rssPerParticle = 0;
    std::uint64_t finalCount = 0, particleFrames = 0, sources = 0;
    for (auto _ : state) {
        const long rss0 = maxRssBytes();
        const std::int64_t live0 = g_live.load();
        g_peak.store(live0);
        select = generate = 0;
        particleFrames = 0;
        {
            Condensation cond;
            SourceTable table;
            std::atomic<std::uint64_t> counted{0};
            for (int t = 0; t < kFrames; ++t) {
                const CondensationView c = cond.at(sc, t);
                const auto t0 = std::chrono::steady_clock::now();
                table = stepSources(table, t, firstCondensation(sc, t), c, sc.mapView(),
                                    sc.primitive(), sc.settings);
                const auto t1 = std::chrono::steady_clock::now();
                std::uint64_t n = 0;
                if (library) {
                    const auto arrays =
                        generateCloudParticles(table, t, c, sc.primitive(), sc.settings);
                    benchmark::DoNotOptimize(arrays.positions.data());
                    n = arrays.levels.size();
                } else {
                    counted = 0;
                    forEachCloudChunk(table, t, c, sc.primitive(), sc.settings,
                                      [&](const CloudChunk& k) {
                                          benchmark::DoNotOptimize(k.positions);
                                          benchmark::ClobberMemory();
                                          counted.fetch_add(k.count, std::memory_order_relaxed);
                                      });
                    n = counted.load();
                }
                const auto t2 = std::chrono::steady_clock::now();
                select += std::chrono::duration<double>(t1 - t0).count();
                generate += std::chrono::duration<double>(t2 - t1).count();
                particleFrames += n;
                finalCount = n;
            }
            sources = table.sources.size();
            if (finalCount != total(cloudCounts(table, kFrames - 1, sc.primitive(), sc.settings))) {
                state.SkipWithError("count differs from Eq. 13");
                return;
            }
        }
        bytesPerParticle =
            static_cast<double>(g_peak.load() - live0) / static_cast<double>(finalCount);
        rssPerParticle =
            static_cast<double>(maxRssBytes() - rss0) / static_cast<double>(finalCount);
    }
    state.counters["select_s"] = select;
    state.counters["generate_s"] = generate;
    state.counters["final_particles"] = static_cast<double>(finalCount);
    state.counters["particle_frames"] = static_cast<double>(particleFrames);
    state.counters["sources"] = static_cast<double>(sources);
    state.counters["heap_B_per_particle"] = bytesPerParticle;
    state.counters["rss_B_per_particle"] = rssPerParticle;
    state.SetItemsProcessed(static_cast<std::int64_t>(particleFrames));
}
BENCHMARK(BM_Figure5)->Arg(0)->Arg(1)->Iterations(1)->UseRealTime()->Unit(benchmark::kMillisecond);

/// The last frame (about 4.5 M particles) of the Figure 5 run.
struct LastFrame {
    Condensation cond;
    CondensationView view;
    std::uint64_t particles = 0;
    LastFrame()
    {
        verifyBitIdentical();  // here, after BM_Figure5, so that its ru_maxrss stays its own
        view = cond.at(scene(), kFrames - 1);
        particles = total(
            cloudCounts(finalSelection().last, kFrames - 1, scene().primitive(), scene().settings));
    }
};
LastFrame& lastFrame()
{
    static LastFrame f;
    return f;
}

void setThroughput(benchmark::State& state, std::uint64_t particles)
{
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(particles));
    state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(particles) *
                            kBytesPerParticle);
    state.counters["particles"] = static_cast<double>(particles);
}

/// generateCloudParticles as GenerateCloud calls it: fresh arrays every frame.
void BM_GenerateLibrary(benchmark::State& state)
{
    const Scene& sc = scene();
    LastFrame& f = lastFrame();
    for (auto _ : state) {
        const auto arrays = generateCloudParticles(finalSelection().last, kFrames - 1, f.view,
                                                   sc.primitive(), sc.settings);
        benchmark::DoNotOptimize(arrays.positions.data());
    }
    setThroughput(state, f.particles);
}
BENCHMARK(BM_GenerateLibrary)->UseRealTime()->Unit(benchmark::kMillisecond);

/// What generateCloudParticles pays for fresh memory alone: three uninitialised frame arrays
/// (17 bytes a particle) allocated and written once in parallel, chunk by chunk (first-touch
/// page faults; the arrays are unmapped again on free).
void BM_FreshFrameArrays(benchmark::State& state)
{
    LastFrame& f = lastFrame();
    for (auto _ : state) {
        CloudParticleArrays out{UninitArray<float>(3 * f.particles),
                                UninitArray<std::uint8_t>(f.particles),
                                UninitArray<std::uint32_t>(f.particles), UninitArray<float>()};
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, f.particles, kCloudChunkParticles),
                          [&](const tbb::blocked_range<std::size_t>& r) {
                              std::fill(out.positions.data() + 3 * r.begin(),
                                        out.positions.data() + 3 * r.end(), 1.0f);
                              std::fill(out.levels.data() + r.begin(), out.levels.data() + r.end(),
                                        std::uint8_t{1});
                              std::fill(out.sources.data() + r.begin(),
                                        out.sources.data() + r.end(), 1u);
                          });
        benchmark::DoNotOptimize(out.positions.data());
        benchmark::DoNotOptimize(out.levels.data());
        benchmark::DoNotOptimize(out.sources.data());
    }
    setThroughput(state, f.particles);
}
BENCHMARK(BM_FreshFrameArrays)->UseRealTime()->Unit(benchmark::kMillisecond);

/// Positions straight into one reused frame buffer (54 MB, larger than L3): DRAM writes.
void BM_GenerateFrameBuffer(benchmark::State& state)
{
    const Scene& sc = scene();
    LastFrame& f = lastFrame();
    std::vector<float> frame(3 * f.particles, 0.0f);
    CloudChunkOptions into;
    into.positionsOut = frame.data();
    for (auto _ : state) {
        forEachCloudChunk(finalSelection().last, kFrames - 1, f.view, sc.primitive(), sc.settings,
                          {}, into);
        benchmark::ClobberMemory();
    }
    setThroughput(state, f.particles);
}
BENCHMARK(BM_GenerateFrameBuffer)->UseRealTime()->Unit(benchmark::kMillisecond);

/// Positions in 4,096-particle chunks into reused per-thread buffers, counted: a streaming
/// consumer's view. The chunks stay in cache; nothing frame-sized is written.
void BM_GenerateStreamed(benchmark::State& state)
{
    const Scene& sc = scene();
    LastFrame& f = lastFrame();
    std::atomic<std::uint64_t> counted{0};
    for (auto _ : state) {
        forEachCloudChunk(finalSelection().last, kFrames - 1, f.view, sc.primitive(), sc.settings,
                          [&](const CloudChunk& k) {
                              benchmark::DoNotOptimize(k.positions);
                              benchmark::ClobberMemory();
                              counted.fetch_add(k.count, std::memory_order_relaxed);
                          });
    }
    if (counted.load() != state.iterations() * f.particles) state.SkipWithError("count differs");
    setThroughput(state, f.particles);
}
BENCHMARK(BM_GenerateStreamed)->UseRealTime()->Unit(benchmark::kMillisecond);

/// Peer: a STREAM-like parallel write of the same 12 bytes a particle (54 MB).
void BM_StreamWrite(benchmark::State& state)
{
    LastFrame& f = lastFrame();
    std::vector<float> frame(3 * f.particles, 0.0f);
    float value = 1.0f;
    for (auto _ : state) {
        tbb::parallel_for(
            tbb::blocked_range<std::size_t>(0, frame.size(), 3 * kCloudChunkParticles),
            [&](const tbb::blocked_range<std::size_t>& r) {
                std::fill(frame.data() + r.begin(), frame.data() + r.end(), value);
            });
        value += 1.0f;
        benchmark::ClobberMemory();
    }
    setThroughput(state, f.particles);
}
BENCHMARK(BM_StreamWrite)->UseRealTime()->Unit(benchmark::kMillisecond);

/// Peer: a STREAM-like parallel copy of the same 54 MB (reads 12 and writes 12 bytes a particle;
/// bytes counted as the 12 written, like the generators).
void BM_StreamCopy(benchmark::State& state)
{
    LastFrame& f = lastFrame();
    std::vector<float> a(3 * f.particles, 1.0f), b(3 * f.particles, 0.0f);
    for (auto _ : state) {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, a.size(), 3 * kCloudChunkParticles),
                          [&](const tbb::blocked_range<std::size_t>& r) {
                              std::memcpy(b.data() + r.begin(), a.data() + r.begin(),
                                          r.size() * sizeof(float));
                          });
        std::swap(a, b);
        benchmark::ClobberMemory();
    }
    setThroughput(state, f.particles);
}
BENCHMARK(BM_StreamCopy)->UseRealTime()->Unit(benchmark::kMillisecond);

/// One frame of the hybrid method at the first frame of the run whose cloud-particle count
/// reaches range(0): the condensation particles' state at t (the stochastic simulation's part;
/// here the scene's closed form), the selection step (Eq. 12-16), then every cloud particle's
/// position (Eq. 10-11) streamed to a counting consumer. The peer of sph_bench's
/// BM_SolverStep at the same particle count: "hybrid vs simulating every particle
/// physically" (bench/run_hybrid_vs_physical.sh prints the ratio).
void BM_HybridStep(benchmark::State& state)
{
    const Scene& sc = scene();
    const auto target = static_cast<std::uint64_t>(state.range(0));
    Condensation cond;
    SourceTable before;
    int frame = -1;
    for (int t = 0; t < kFrames; ++t) {
        SourceTable next = stepSources(before, t, firstCondensation(sc, t), cond.at(sc, t),
                                       sc.mapView(), sc.primitive(), sc.settings);
        if (total(cloudCounts(next, t, sc.primitive(), sc.settings)) >= target) {
            frame = t;
            break;
        }
        before = std::move(next);
    }
    if (frame < 0) {
        state.SkipWithError("the scene never reaches that many cloud particles");
        return;
    }
    std::uint64_t particles = 0;
    for (auto _ : state) {
        const CondensationView c = cond.at(sc, frame);
        const SourceTable table = stepSources(before, frame, firstCondensation(sc, frame), c,
                                              sc.mapView(), sc.primitive(), sc.settings);
        std::atomic<std::uint64_t> counted{0};
        forEachCloudChunk(table, frame, c, sc.primitive(), sc.settings, [&](const CloudChunk& k) {
            benchmark::DoNotOptimize(k.positions);
            counted.fetch_add(k.count, std::memory_order_relaxed);
        });
        particles = counted.load();
    }
    state.counters["particles"] = static_cast<double>(particles);
    state.counters["frame"] = frame;
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(particles));
}
BENCHMARK(BM_HybridStep)
    ->Arg(64000)
    ->Arg(256000)
    ->Arg(1000000)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

/// --scene-info: the scene's counts per level every 51 frames, and the selection's time.
void printSceneInfo()
{
    const Scene& sc = scene();
    Condensation cond;
    SourceTable table;
    std::printf(
        "primitive: %d frames, N_f %u .. %u, %.1f MB; map %d x %d; %zu condensation particles\n",
        kPrimitiveFrames, sc.counts.front(), sc.counts.back(),
        static_cast<double>(sc.primitiveBytes) / 1e6, kMapX, kMapY, kCondensation);
    std::uint64_t particleFrames = 0;
    for (int t = 0; t < kFrames; ++t) {
        const CondensationView c = cond.at(sc, t);
        table = stepSources(table, t, firstCondensation(sc, t), c, sc.mapView(), sc.primitive(),
                            sc.settings);
        const auto counts = cloudCounts(table, t, sc.primitive(), sc.settings);
        particleFrames += total(counts);
        if (t % 51 == 0 || t == kFrames - 1) {
            std::vector<int> g(4, 0);
            for (const Source& s : table.sources) ++g[s.level - 1u];
            std::printf(
                "frame %3d: L_max %d, sources %d/%d/%d/%d, cloud particles %llu/%llu/%llu/%llu = "
                "%llu\n",
                t, table.topLevel, g[0], g[1], g[2], g[3],
                static_cast<unsigned long long>(counts[0]),
                static_cast<unsigned long long>(counts[1]),
                static_cast<unsigned long long>(counts[2]),
                static_cast<unsigned long long>(counts[3]),
                static_cast<unsigned long long>(total(counts)));
        }
    }
    std::printf("particle-frames over the run: %llu; table: %zu sources, %zu bytes\n",
                static_cast<unsigned long long>(particleFrames), table.sources.size(),
                table.sources.size() * sizeof(Source) + table.condensationTaken.size() +
                    table.cloudTaken.size() * sizeof(std::uint64_t));
}

}  // namespace

int main(int argc, char** argv)
{
    for (int i = 1; i < argc; ++i)
        if (std::string(argv[i]) == "--scene-info") {
            printSceneInfo();
            return 0;
        }
    scene();  // the inputs exist before any measurement (they are not the mapper's memory)
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
