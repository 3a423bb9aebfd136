// cloudgraph validate GRAPH [--set node.param=value]... [--plugin PATH]... [--python-nodes FILE]...

#include <cstdio>

#include "cli/Commands.h"
#include "cli/Common.h"
#include "core/Error.h"
#include "nodes/volume/VolumeNodes.h"

namespace cg::cli {

int validateCommand(const Args& args)
{
    OptionParser opts(args, "validate");
    return guarded([&] {
        opts.parse();
        Registry registry;
        const Graph graph = loadGraphFromOptions(opts, registry, "validate");
        // Loading leaves the voxels of a VDB input to the cook, where a value that is not
        // finite is refused; validate reads them, so that it passes no graph `run` refuses.
        for (const GraphNode& node : graph.nodes()) {
            if (node.decl->type != "ReadVDB") continue;
            const std::string place =
                graph.sourceName().empty() ? node.pointer : graph.sourceName() + ":" + node.pointer;
            try {
                checkReadVdbVoxels(node.params, place, graph.limits.allocationLimitBytes);
            } catch (const InputError& e) {
                throw InputError(e.where(), e.message() + " (node '" + node.id + "')");
            }
        }
        std::printf("%s: valid, %zu nodes, frames %d:%d\n", opts.positionals()[0].c_str(),
                    graph.nodes().size(), graph.frames.start, graph.frames.end);
        return kExitOk;
    });
}

}  // namespace cg::cli
