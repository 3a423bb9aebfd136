// PrimitiveSubset: every k-th particle of a primitive set, so each mapped copy carries fewer
// cloud particles (see docs/mapper.md, "A caution on counts").

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/PrimitiveSet.h"
#include "nodes/mapping/MappingNodes.h"

namespace cg {

namespace {

/// Keeps ids 0, k, 2k, ... of `full`. Ids appear in order, so frame s keeps
/// ceil(N_f(s) / k) particles and the subset is again a primitive set (stable ids in order of
/// appearance, N_f non-decreasing); each kept particle follows its physical trajectory.
std::shared_ptr<PrimitiveSetData> everyKth(const PrimitiveSetData& full, std::uint32_t k)
{
    std::vector<std::uint32_t> counts;
    counts.reserve(full.counts.size());
    std::uint64_t total = 0;
    for (std::uint32_t n : full.counts) {
        counts.push_back((n + k - 1) / k);
        total += counts.back();
    }
    std::vector<float> positions;
    positions.reserve(3 * total);
    for (int s = 0; s < full.frames(); ++s) {
        const float* frame = full.frame(s);
        for (std::uint32_t id = 0; id < full.count(s); id += k)
            positions.insert(positions.end(), frame + 3 * std::size_t{id}, frame + 3 * std::size_t{id} + 3);
    }
    return std::make_shared<PrimitiveSetData>(full.frameTime, std::move(counts), std::move(positions));
}

class PrimitiveSubsetNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto full = ctx.input<PrimitiveSetData>("primitive");
        // k = ceil(N_f(last) / K), so about K particles remain at the last frame.
        const auto target = static_cast<std::uint64_t>(ctx.params().getInt("particles"));
        const std::uint64_t last = full->frames() > 0 ? full->count(full->frames() - 1) : 0;
        const auto k = static_cast<std::uint32_t>(std::max<std::uint64_t>(1, (last + target - 1) / target));
        ctx.setOutput("primitive", k == 1 ? full : everyKth(*full, k));
    }
};

}  // namespace

void registerPrimitiveSubsetNode(Registry& registry)
{
    NodeDecl d;
    d.type = "PrimitiveSubset";
    d.category = "mapping";
    d.doc =
        "Every k-th particle of a primitive set (ids 0, k, 2k, ... in order of appearance), as "
        "a primitive set again, with k = ceil(N_f(last) / K) so that about K particles remain "
        "at the last frame: frame s keeps ceil(N_f(s) / k), each on its physical trajectory. Ours, not the paper's: Eq. 14 selects M[L] x N_c[L-1] sources from the "
        "cloud particles of the level below, so the counts multiply by about M x N_f per "
        "level; a thinned primitive keeps a deep recursion (L_max 5) within millions of cloud "
        "particles, as the paper's Table 1 counts imply (Figure 6: 492,646). Give the "
        "voxelizer a larger particle radius to fill the gaps. Every copy then carries the same "
        "particles, which line up in horizontal bands across a mapped cloud: for mapping, "
        "PrimitiveMapper's particlesPerCopy (a different subset per copy) looks better.";
    d.inputs = {port("primitive", "PrimitiveSet", "the full primitive set")};
    d.outputs = {port("primitive", "PrimitiveSet", "ids 0, k, 2k, ... of the input, renumbered 0, 1, 2, ...")};
    d.params = {intParam("particles", 16384, "particles",
                         "K: about this many particles remain at the last frame (value ours; at "
                         "least N_f(last) keeps all)", 1, 1 << 30)};
    d.create = [] { return std::make_unique<PrimitiveSubsetNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
