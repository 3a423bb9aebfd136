#include "golden/GoldenRun.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "core/Evaluator.h"
#include "core/Graph.h"
#include "core/Registry.h"
#include "golden/GoldenFiles.h"
#include "nodes/Builtin.h"
#include "support/TestUtil.h"

namespace cg::golden {

std::filesystem::path graphsDir()
{
    return std::filesystem::path(CLOUDGRAPH_SOURCE_DIR) / "graphs";
}
std::filesystem::path expectedDir()
{
    return std::filesystem::path(CLOUDGRAPH_SOURCE_DIR) / "tests/golden/expected";
}

namespace {

/// Every node but the sinks left out (EncodeVideo): each is recorded at every golden frame,
/// also where only a writer idle on that frame reads it.
std::vector<std::string> targetsOf(const Graph& g, const GoldenSpec& spec)
{
    const std::vector<std::size_t> sinks = g.sinks();
    for (const std::string& id : spec.notCooked)
        if (std::find(sinks.begin(), sinks.end(), g.indexOf(id)) == sinks.end())
            throw std::invalid_argument(spec.name + ": '" + id +
                                        "' is not a sink; leave out sinks only");
    std::vector<std::string> targets;
    for (const GraphNode& node : g.nodes())
        if (std::find(spec.notCooked.begin(), spec.notCooked.end(), node.id) ==
            spec.notCooked.end())
            targets.push_back(node.id);
    return targets;
}

void addOutputs(Stats& all, const std::string& prefix, const OutputMap& outputs)
{
    for (const auto& [port, value] : outputs) {
        if (!value) continue;
        for (const auto& [name, stat] : statsOf(*value)) all[prefix + port + "/" + name] = stat;
    }
}

}  // namespace

Stats runGolden(const GoldenSpec& spec, const std::vector<std::string>& overrides)
{
    Registry registry;
    registerBuiltinNodes(registry);
    Graph g = loadGraph(graphsDir() / (spec.name + ".json"), registry);
    if (spec.frames.empty() || !std::is_sorted(spec.frames.begin(), spec.frames.end()) ||
        spec.frames.front() < g.frames.start || spec.frames.back() > g.frames.end)
        throw std::invalid_argument(
            spec.name + ": the recorded frames must be ascending, inside the graph's range");
    spec.shrink(g);
    for (const std::string& o : overrides) applySetOverride(g, o);
    g.frames.end = spec.frames.back();  // the small version's range: nothing after it cooks
    const std::vector<std::string> targets = targetsOf(g, spec);

    test::TempDir out;
    EvaluatorOptions options;
    options.outDir = out.path();
    Evaluator ev(registry, options);
    Stats all;
    std::map<std::string, OutputsPtr> recorded;  // what each node gave at the last recorded frame
    for (int frame : spec.frames) {
        Evaluator::FrameOutputs results;
        ev.cookFrames(g, frame, frame, targets,
                      [&](int, const Evaluator::FrameOutputs& r) { results = r; });
        char prefix[32];
        std::snprintf(prefix, sizeof prefix, "%04d/", frame);
        for (std::size_t i = 0; i < results.size(); ++i) {
            const std::string& id = g.nodes()[i].id;
            // A value the memory cache gave again is the same value: record it once.
            if (!results[i] || recorded[id] == results[i]) continue;
            recorded[id] = results[i];
            addOutputs(all, prefix + id + ".", *results[i]);
        }
    }
    for (const auto& [name, stat] : fileStats(out.path())) all[name] = stat;
    return all;
}

}  // namespace cg::golden
