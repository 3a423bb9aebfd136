// cloudgraph dot GRAPH: the graph as Graphviz, for `dot -Tsvg`.

#include <cstdio>

#include "cli/Commands.h"
#include "cli/Common.h"
#include "core/Error.h"
#include "core/Graph.h"

namespace cg::cli {

int dotCommand(const Args& args)
{
    OptionParser opts(args, "dot");
    return guarded([&] {
        opts.parse();
        if (opts.positionals().size() != 1)
            throw InputError("command line", "dot needs exactly one graph file");
        Registry registry;
        buildRegistry(registry, opts);
        const Graph graph = loadGraph(opts.positionals()[0], registry);
        std::printf(
            "digraph cloudgraph {\n  rankdir=LR;\n  node [shape=box, fontname=\"Helvetica\"];\n");
        for (std::size_t i : graph.topologicalOrder()) {
            const GraphNode& n = graph.nodes()[i];
            const char* style = n.decl->simulation    ? ", style=rounded"
                                : n.decl->writesFiles ? ", style=bold"
                                                      : "";
            std::printf("  \"%s\" [label=\"%s\\n%s\"%s];\n", n.id.c_str(), n.id.c_str(),
                        n.decl->type.c_str(), style);
        }
        for (std::size_t i : graph.topologicalOrder()) {
            const GraphNode& n = graph.nodes()[i];
            for (const auto& [port, conn] : n.inputs)
                std::printf("  \"%s\" -> \"%s\" [label=\"%s -> %s\"];\n", conn.node.c_str(),
                            n.id.c_str(), conn.port.c_str(), port.c_str());
        }
        std::printf("}\n");
        return kExitOk;
    });
}

}  // namespace cg::cli
