// cloudgraph run GRAPH [--frames A:B] [--set node.param=value]... [--cache DIR] [--out DIR]
//                      [--threads N] [--report FILE] [--plugin PATH]...

#include <csignal>
#include <cstdio>
#include <memory>

#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include "cli/Commands.h"
#include "cli/Common.h"
#include "cli/ProgressBar.h"
#include "core/AtomicFile.h"
#include "core/Error.h"
#include "core/Evaluator.h"
#include "core/Graph.h"

namespace cg::cli {

namespace {

std::shared_ptr<CancelToken> gCancel;

void writeReport(const std::string& path, const nlohmann::json& report)
{
    const std::filesystem::path p(path);
    if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
    writeFileAtomically(p, report.dump(2));
}

extern "C" void onInterrupt(int) { if (gCancel) gCancel->cancel(); }

FrameRange parseFrames(const std::string& text, const FrameRange& graphRange)
{
    FrameRange r;
    try {
        std::size_t used = 0;
        const auto colon = text.find(':');
        r.start = std::stoi(text.substr(0, colon), &used);
        if (used != (colon == std::string::npos ? text.size() : colon)) throw std::invalid_argument("");
        r.end = r.start;
        if (colon != std::string::npos) {
            const std::string rest = text.substr(colon + 1);
            r.end = std::stoi(rest, &used);
            if (used != rest.size()) throw std::invalid_argument("");
        }
    } catch (const std::exception&) {
        throw InputError("--frames", "'" + text + "' is not a frame or a range A:B");
    }
    if (r.end < r.start || r.start < graphRange.start || r.end > graphRange.end) {
        throw InputError("--frames", "range " + text + " is not inside the graph's frames " +
                                         std::to_string(graphRange.start) + ":" +
                                         std::to_string(graphRange.end));
    }
    return r;
}

int parseThreads(const std::string& text)
{
    try {
        std::size_t used = 0;
        const int n = std::stoi(text, &used);
        if (used == text.size() && n >= 1 && n <= 1024) return n;
    } catch (const std::exception&) {
    }
    throw InputError("--threads", "'" + text + "' is not a thread count between 1 and 1024");
}

}  // namespace

int runCommand(const Args& args)
{
    OptionParser opts(args);
    declareGraphOptions(opts);
    for (const char* o : {"--frames", "--cache", "--out", "--threads", "--report", "--cache-memory-mb"})
        opts.valueOption(o);
    return guarded([&] {
        opts.parse();
        std::optional<tbb::global_control> threadLimit;
        if (auto t = opts.value("--threads"))
            threadLimit.emplace(tbb::global_control::max_allowed_parallelism, parseThreads(*t));

        Registry registry;
        const Graph graph = loadGraphFromOptions(opts, registry, "run");
        const FrameRange frames =
            opts.value("--frames") ? parseFrames(*opts.value("--frames"), graph.frames) : graph.frames;

        EvaluatorOptions evalOptions;
        evalOptions.outDir = opts.value("--out").value_or("out");
        if (auto c = opts.value("--cache")) evalOptions.diskCache = std::make_shared<DiskCache>(*c);
        if (auto m = opts.value("--cache-memory-mb")) {
            try {
                evalOptions.memoryBudgetBytes = std::stoull(*m) << 20;
            } catch (const std::exception&) {
                throw InputError("--cache-memory-mb", "'" + *m + "' is not a number");
            }
        }
        gCancel = evalOptions.cancel;
        std::signal(SIGINT, onInterrupt);
        std::signal(SIGTERM, onInterrupt);
        ProgressBar bar(!opts.has("-q"));
        evalOptions.onProgress = [&bar](const Progress& p) { bar.update(p); };

        Evaluator evaluator(registry, evalOptions);
        const auto t0 = std::chrono::steady_clock::now();
        try {
            evaluator.cookFrames(graph, frames.start, frames.end);
        } catch (...) {
            bar.finish();
            // Write the report even for a failed run: it shows what did cook.
            if (auto r = opts.value("--report")) {
                nlohmann::json j = evaluator.report().toJson();
                j["failed"] = true;
                writeReport(*r, j);
            }
            throw;
        }
        bar.finish();
        const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        nlohmann::json report = evaluator.report().toJson();
        report["graph"] = opts.positionals()[0];
        report["frames"] = {frames.start, frames.end};
        report["wallSeconds"] = wall;
        report["failed"] = false;
        if (auto r = opts.value("--report")) writeReport(*r, report);
        const auto& totals = report["totals"];
        spdlog::info("cooked frames {}..{} in {:.2f} s: {} cooks, {} memory hits, {} disk hits",
                     frames.start, frames.end, wall, totals["cooked"].get<std::size_t>(),
                     totals["memoryHits"].get<std::size_t>(), totals["diskHits"].get<std::size_t>());
        return kExitOk;
    });
}

}  // namespace cg::cli
