// cloudgraph run GRAPH [options]: cooks a graph for its frames. The options and their help
// are in cli/CommandTable.cc (`cloudgraph run --help`).

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include "cli/Commands.h"
#include "cli/Common.h"
#include "cli/FarmToken.h"
#include "cli/FrameChunks.h"
#include "cli/ProgressBar.h"
#include "core/CacheBound.h"
#include "core/Error.h"
#include "core/Evaluator.h"
#include "core/Graph.h"
#include "util/AtomicFile.h"

namespace cg::cli {

namespace {

std::shared_ptr<CancelToken> gCancel;

/// 1 TiB: more than any machine we run on, small enough that << 20 cannot overflow.
constexpr std::int64_t kMaxCacheMemoryMiB = std::int64_t{1} << 20;

/// Throws InputError naming --report: the user chose the place.
void writeReport(const std::string& path, const nlohmann::json& report)
{
    try {
        const std::filesystem::path p(path);
        if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
        util::writeFileAtomically(p, report.dump(2));
    } catch (const std::exception& e) {
        throw InputError("--report " + path, std::string("cannot write the report: ") + e.what());
    }
}

extern "C" void onInterrupt(int)
{
    if (gCancel) gCancel->cancel();
}

/// --frames, or chunk --task (SLURM_ARRAY_TASK_ID) of --chunk frames of that range.
FrameRange framesToCook(const OptionParser& opts, const Graph& graph)
{
    const FrameRange range = opts.value("--frames")
                                 ? parseFrameRange(*opts.value("--frames"), graph.frames)
                                 : graph.frames;
    const auto chunk = opts.value("--chunk");
    if (!chunk) {
        if (opts.has("--task")) throw InputError("--task", "needs --chunk N (frames per chunk)");
        return range;
    }
    const char* slurmTask = std::getenv("SLURM_ARRAY_TASK_ID");
    return chunkFrames(range, parseChunkSize(*chunk), opts.value("--task"),
                       slurmTask ? std::optional<std::string>(slurmTask) : std::nullopt);
}

/// The ids of the graph's simulation nodes: what --simulations-only cooks (with what they
/// read), so that a farm's frame jobs find every simulation state in the shared cache.
std::vector<std::string> simulationNodes(const Graph& graph)
{
    std::vector<std::string> ids;
    for (const GraphNode& node : graph.nodes())
        if (node.decl->simulation) ids.push_back(node.id);
    if (ids.empty()) spdlog::info("the graph has no simulation nodes: nothing to cook");
    return ids;
}

/// What a chunk cooks: the graph's sinks, with each node that gathers every frame's files
/// (EncodeVideo), which would find other chunks' frames missing, replaced by its inputs.
std::vector<std::string> targetsOfOneChunk(const Graph& graph)
{
    std::vector<std::size_t> stack = graph.sinks();
    std::vector<bool> seen(graph.nodes().size(), false);
    std::vector<std::string> ids;
    while (!stack.empty()) {
        const std::size_t idx = stack.back();
        stack.pop_back();
        if (seen[idx]) continue;
        seen[idx] = true;
        const GraphNode& node = graph.nodes()[idx];
        if (!node.decl->gathersFrames) {
            ids.push_back(node.id);
            continue;
        }
        spdlog::info("{} ({}) gathers every frame: a chunk leaves it out", node.id,
                     node.decl->type);
        for (std::size_t up : graph.upstream()[idx]) stack.push_back(up);
    }
    return ids;
}

/// The nodes --only names (none: the graph's sinks), each checked to be in the graph; --only
/// does not mix with --chunk or --simulations-only, which choose their own nodes.
std::vector<std::string> onlyNodes(const OptionParser& opts, const Graph& graph)
{
    const std::vector<std::string> ids = opts.values("--only");
    if (ids.empty()) return {};
    for (const char* other : {"--chunk", "--simulations-only"})
        if (opts.has(other))
            throw InputError("--only", std::string("does not go with ") + other +
                                           ", which chooses the nodes itself");
    for (const std::string& id : ids)
        if (!graph.find(id)) throw InputError("--only " + id, "the graph has no node '" + id + "'");
    return ids;
}

/// Refuses, before anything cooks, an --out that is not a directory and a --report that
/// names one: found after the cook, they would cost the whole run.
void checkOutputLocations(const OptionParser& opts)
{
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path out = opts.value("--out").value_or("out");
    if (fs::exists(out, ec) && !fs::is_directory(out, ec))
        throw InputError("--out " + out.string(), "is not a directory");
    if (opts.has("--simulations-only") && !opts.value("--cache"))
        throw InputError("--simulations-only",
                         "needs --cache DIR: the states are cooked to be kept there");
    if (const auto report = opts.value("--report")) {
        const fs::path file(*report);
        if (report->empty() || report->back() == '/' || fs::is_directory(file, ec))
            throw InputError("--report " + *report, "names a directory, not a file");
        if (file.has_parent_path() && fs::exists(file.parent_path(), ec) &&
            !fs::is_directory(file.parent_path(), ec))
            throw InputError("--report " + *report, "its directory is a file");
    }
}

/// --cache-limit in bytes: what the disk cache is pruned to after the run (none: unbounded).
std::optional<std::uint64_t> cacheLimit(const OptionParser& opts)
{
    const auto limit = opts.value("--cache-limit");
    if (!limit) return std::nullopt;
    if (!opts.value("--cache")) throw InputError("--cache-limit", "needs --cache DIR");
    return parseByteSize(*limit, "--cache-limit");
}

/// Prunes the cache to `limit` and says what went, in the log and the report.
void boundCache(const std::string& cache, std::uint64_t limit, nlohmann::json& report)
{
    const CacheUsage removed = pruneCache(cache, limit);
    if (removed.entries > 0)
        spdlog::info(
            "cache: removed {} least recently used entries ({:.1f} MiB) to stay "
            "within --cache-limit",
            removed.entries, static_cast<double>(removed.bytes) / (1 << 20));
    report["cachePruned"] = {{"entries", removed.entries}, {"bytes", removed.bytes}};
}

}  // namespace

int runCommand(const Args& args)
{
    OptionParser opts(args, "run");
    return guarded([&] {
        opts.parse();
        std::optional<tbb::global_control> threadLimit;
        if (auto t = opts.value("--threads"))
            threadLimit.emplace(tbb::global_control::max_allowed_parallelism,
                                parseIntegerOption(*t, "--threads", "a thread count", 1, 1024));
        checkOutputLocations(opts);
        const std::optional<std::uint64_t> limit = cacheLimit(opts);

        Registry registry;
        const Graph graph = loadGraphFromOptions(opts, registry, "run");
        const FrameRange frames = framesToCook(opts, graph);
        const std::vector<std::string> targets = opts.has("--simulations-only")
                                                     ? simulationNodes(graph)
                                                 : opts.has("--chunk") ? targetsOfOneChunk(graph)
                                                                       : onlyNodes(opts, graph);

        EvaluatorOptions evalOptions;
        evalOptions.outDir = opts.value("--out").value_or("out");
        if (auto c = opts.value("--cache")) evalOptions.diskCache = std::make_shared<DiskCache>(*c);
        if (auto token = opts.value("--farm-token")) {
            if (!evalOptions.diskCache)
                throw InputError("--farm-token", "needs the farm's --cache");
            checkFarmToken(*evalOptions.diskCache, *token);
        }
        if (auto m = opts.value("--cache-memory-mb"))
            evalOptions.memoryBudgetBytes =
                static_cast<std::uint64_t>(parseIntegerOption(
                    *m, "--cache-memory-mb", "a size in MiB", 0, kMaxCacheMemoryMiB))
                << 20;
        // After every option is checked: a refused option creates no --out.
        if (!(opts.has("--simulations-only") && targets.empty()))
            checkOutputPlaces(graph, targets, frames, evalOptions.outDir);
        gCancel = evalOptions.cancel;
        std::signal(SIGINT, onInterrupt);
        std::signal(SIGTERM, onInterrupt);
        ProgressBar bar(!opts.has("-q"));
        evalOptions.onProgress = [&bar](const Progress& p) { bar.update(p); };

        Evaluator evaluator(registry, evalOptions);
        const auto t0 = std::chrono::steady_clock::now();
        try {
            // Empty targets mean the graph's sinks, except for a graph with no simulation.
            if (!(opts.has("--simulations-only") && targets.empty()))
                evaluator.cookFrames(graph, frames.start, frames.end, targets);
        } catch (...) {
            bar.finish();
            // Write the report even for a failed run: it shows what did cook. A report that
            // cannot be written must not hide the error that failed the run.
            if (auto r = opts.value("--report")) {
                nlohmann::json j = evaluator.report().toJson();
                j["failed"] = true;
                try {
                    writeReport(*r, j);
                } catch (const InputError& e) {
                    spdlog::error("{}", e.what());
                }
            }
            throw;
        }
        bar.finish();
        const double wall =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        nlohmann::json report = evaluator.report().toJson();
        report["graph"] = opts.positionals()[0];
        report["frames"] = {frames.start, frames.end};
        report["wallSeconds"] = wall;
        report["failed"] = false;
        if (limit) boundCache(*opts.value("--cache"), *limit, report);
        if (auto r = opts.value("--report")) writeReport(*r, report);
        const auto& totals = report["totals"];
        spdlog::info("cooked frames {}..{} in {:.2f} s: {} cooks, {} memory hits, {} disk hits",
                     frames.start, frames.end, wall, totals["cooked"].get<std::size_t>(),
                     totals["memoryHits"].get<std::size_t>(),
                     totals["diskHits"].get<std::size_t>());
        return kExitOk;
    });
}

}  // namespace cg::cli
