// cloudgraph validate GRAPH [--set node.param=value]... [--plugin PATH]...

#include <cstdio>

#include "cli/Commands.h"
#include "cli/Common.h"
#include "core/Error.h"
#include "core/Graph.h"

namespace cg::cli {

int validateCommand(const Args& args)
{
    OptionParser opts(args);
    opts.valueOption("--set");
    opts.valueOption("--plugin");
    opts.flag("--allow-outside-out");
    return guarded([&] {
        opts.parse();
        if (opts.positionals().size() != 1)
            throw InputError("command line", "validate needs exactly one graph file");
        Registry registry;
        buildRegistry(registry, opts.values("--plugin"));
        LoadOptions loadOptions;
        loadOptions.allowPathsOutsideOut = opts.has("--allow-outside-out");
        Graph graph = loadGraph(opts.positionals()[0], registry, loadOptions);
        for (const std::string& s : opts.values("--set")) applySetOverride(graph, s);
        std::printf("%s: valid, %zu nodes, frames %d:%d\n", opts.positionals()[0].c_str(),
                    graph.nodes().size(), graph.frames.start, graph.frames.end);
        return kExitOk;
    });
}

}  // namespace cg::cli
