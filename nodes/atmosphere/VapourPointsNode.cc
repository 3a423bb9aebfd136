// VapourPoints: the stochastic simulation's water vapour and condensation particles as points
// for the Voxelizer and the particle writers (Figure 5 renders them lighter than the cloud).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/atmosphere/AtmosphereNodes.h"
#include "nodes/data/CloudParticles.h"
#include "nodes/data/VapourParticles.h"

namespace cg {

namespace {

class VapourPointsNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto c = ctx.input<CondensationData>("condensation");
        const std::string& which = ctx.params().getString("which");
        const bool wantVapour = which != "condensation", wantCondensed = which != "vapour";
        const VapourParticlesData& v = *c->particles;
        const VapourStatics& st = *v.statics;
        const std::vector<float>& x = v.xs();
        const std::vector<float>& y = v.ys();
        std::vector<float> positions;
        std::vector<std::uint32_t> ids;
        for (std::size_t i = 0; i < v.size(); ++i) {
            if (!(c->condensed(i) ? wantCondensed : wantVapour)) continue;
            positions.insert(positions.end(), {x[i], y[i], v.z[i]});
            ids.push_back(st.id[i]);
        }
        // Level 0 marks points that are not cloud particles; the source field holds the id.
        const std::vector<std::uint8_t> levels(ids.size(), 0);
        ctx.setOutput("particles", std::make_shared<CloudParticlesData>(positions, levels, ids));
    }
};

}  // namespace

void registerVapourPointsNode(Registry& registry)
{
    NodeDecl d;
    d.type = "VapourPoints";
    d.version = 2;  // each version's change: CHANGES.md, "Node versions"
    d.category = "atmosphere";
    d.doc =
        "The water vapour particles of this frame, the condensation particles, or both, as "
        "points (CloudParticles of level 0 whose source field is the particle id), in "
        "particle order: feed a Voxelizer with a low density and CombineVolumes to render them "
        "lighter than the cloud particles, as Figure 5 does, or WriteCloudParticles to export "
        "them.";
    d.inputs = {
        port("condensation", "Condensation", "the vapour particles and which have condensed")};
    d.outputs = {port("particles", "CloudParticles", "the selected particles, level 0")};
    d.params = {stringParam("which", "all",
                            "vapour (not yet condensed), condensation, or all particles",
                            {"vapour", "condensation", "all"})};
    d.create = [] { return std::make_unique<VapourPointsNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
