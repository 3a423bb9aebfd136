// PrimitiveSubset: every k-th particle of a primitive set, so each mapped copy carries fewer
// cloud particles (see docs/mapper.md, "A caution on counts").

#include <cstdint>
#include <vector>

#include "algo/mapping/PrimitiveSubset.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/PrimitiveSet.h"
#include "nodes/mapping/MappingNodes.h"

namespace cg {

namespace {

class PrimitiveSubsetNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto full = ctx.input<PrimitiveSetData>("primitive");
        // k = ceil(N_f(last) / K), so about K particles remain at the last frame.
        const auto target = static_cast<std::uint64_t>(ctx.params().getInt("particles"));
        const std::uint64_t last = full->frames() > 0 ? full->count(full->frames() - 1) : 0;
        const std::uint32_t k = algo::subsetStride(last, target);
        if (k == 1) {
            ctx.setOutput("primitive", full);
            return;
        }
        std::vector<std::uint32_t> counts;
        std::vector<float> positions;
        algo::everyKthParticle(full->counts, full->positions, k, counts, positions);
        ctx.setOutput("primitive", std::make_shared<PrimitiveSetData>(
                                       full->frameTime, std::move(counts), std::move(positions)));
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
        "at the last frame: frame s keeps ceil(N_f(s) / k), each on its physical trajectory. Ours, "
        "not the paper's: Eq. 14 selects M[L] x N_c[L-1] sources from the "
        "cloud particles of the level below, so the counts multiply by about M x N_f per "
        "level; a thinned primitive keeps a deep recursion (L_max 5) within millions of cloud "
        "particles, as the paper's Table 1 counts imply (Figure 6: 492,646). Give the "
        "voxelizer a larger particle radius to fill the gaps. Every copy then carries the same "
        "particles, which line up in horizontal bands across a mapped cloud: for mapping, "
        "PrimitiveMapper's particlesPerCopy (a different subset per copy) looks better.";
    d.inputs = {port("primitive", "PrimitiveSet", "the full primitive set")};
    d.outputs = {port("primitive", "PrimitiveSet",
                      "ids 0, k, 2k, ... of the input, renumbered 0, 1, 2, ...")};
    d.params = {intParam("particles", 16384, "particles",
                         "K: about this many particles remain at the last frame (value ours; at "
                         "least N_f(last) keeps all)",
                         1, 1 << 30)};
    d.create = [] { return std::make_unique<PrimitiveSubsetNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
