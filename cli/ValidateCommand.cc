// cloudgraph validate GRAPH [--set node.param=value]... [--plugin PATH]... [--python-nodes FILE]...

#include <cstdio>

#include "cli/Commands.h"
#include "cli/Common.h"

namespace cg::cli {

int validateCommand(const Args& args)
{
    OptionParser opts(args);
    declareGraphOptions(opts);
    return guarded([&] {
        opts.parse();
        Registry registry;
        const Graph graph = loadGraphFromOptions(opts, registry, "validate");
        std::printf("%s: valid, %zu nodes, frames %d:%d\n", opts.positionals()[0].c_str(),
                    graph.nodes().size(), graph.frames.start, graph.frames.end);
        return kExitOk;
    });
}

}  // namespace cg::cli
