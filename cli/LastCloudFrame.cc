#include "cli/LastCloudFrame.h"

#include <algorithm>
#include <vector>

#include "core/NodeDecl.h"

namespace cg::cli {

std::optional<int> lastFrameWithParticles(const std::function<std::size_t(int)>& particlesAt,
                                          int start, int end, int stride)
{
    stride = std::max(stride, 1);
    for (int f = end; f >= start; f -= stride) {
        if (particlesAt(f) == 0) continue;
        // The sample after f (f + stride) had none: look at the frames between, latest first.
        for (int g = std::min(end, f + stride - 1); g > f; --g)
            if (particlesAt(g) != 0) return g;
        return f;
    }
    return std::nullopt;
}

std::optional<std::pair<std::string, std::string>> cloudSourceOf(const Graph& graph,
                                                                 const std::string& node)
{
    if (!graph.find(node)) return std::nullopt;
    const std::size_t target = graph.indexOf(node);
    std::vector<bool> above(graph.nodes().size(), false);
    above[target] = true;
    const std::vector<std::size_t>& order = graph.topologicalOrder();
    for (auto it = order.rbegin(); it != order.rend(); ++it) {
        if (!above[*it]) continue;
        for (const PortDecl& out : graph.nodes()[*it].decl->outputs)
            if (out.type == "CloudParticles") return std::pair{graph.nodes()[*it].id, out.name};
        for (const std::size_t up : graph.upstream()[*it]) above[up] = true;
    }
    return std::nullopt;
}

}  // namespace cg::cli
