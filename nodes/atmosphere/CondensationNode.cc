// Condensation: vapour particles colder than the dew point become condensation particles
// (pseudocode lines 9-14); records when each condensed and when the first one did.

#include <algorithm>

#include "core/CoreData.h"
#include "core/Error.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/atmosphere/AtmosphereNodes.h"
#include "nodes/data/AtmosphereData.h"
#include "nodes/data/VapourParticles.h"

namespace cg {

namespace {

class CondensationNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto particles = ctx.input<VapourParticlesData>("particles");
        const double dewPoint = ctx.input<AtmosphereData>("atmosphere")->atmosphere.dewPoint;
        const auto previous = ctx.previous<CondensationData>("condensation");
        const std::size_t n = particles->size();

        std::vector<std::int32_t> frames(n, -1);
        std::int32_t first = -1;
        if (previous) {
            if (previous->condensedFrame.size() != n)
                throw InputError(ctx.nodeId(), "the particle count changed during the simulation");
            frames = previous->condensedFrame;
            first = previous->firstFrame;
        }
        // Condensation is one-way: a condensation particle never turns back into vapour.
        const auto frame = static_cast<std::int32_t>(ctx.frame());
        std::size_t count = 0;
        for (std::size_t i = 0; i < n; ++i) {
            if (frames[i] < 0 && particles->temperature[i] < dewPoint) frames[i] = frame;
            if (frames[i] >= 0) ++count;
        }
        if (first < 0 && count > 0) first = frame;
        ctx.setOutput("condensation", std::make_shared<CondensationData>(particles, std::move(frames), first));
        ctx.setOutput("firstFrame", std::make_shared<IntData>(first));
        ctx.setOutput("count", std::make_shared<IntData>(static_cast<std::int64_t>(count)));
    }
};

}  // namespace

void registerCondensationNode(Registry& registry)
{
    NodeDecl d;
    d.type = "Condensation";
    d.category = "atmosphere";
    d.doc = "Marks vapour particles whose temperature T_v has fallen below the dew point T_dp as "
            "condensation particles (pseudocode lines 9-14) and remembers the frame at which each "
            "condensed; once condensed, a particle stays a condensation particle. Also gives the "
            "frame at which the first condensation particle appeared: t_s[1] of Sec. 5.2. A "
            "simulation: each frame builds on the previous one.";
    d.simulation = true;
    d.inputs = {port("particles", "VapourParticles", "the particles at this frame"),
                port("atmosphere", "Atmosphere", "the environment (its dew point T_dp)")};
    d.outputs = {port("condensation", "Condensation", "the particles with their condensation frames"),
                 port("firstFrame", "Int", "frame of the first condensation (t_s[1]); -1 if none yet"),
                 port("count", "Int", "number of condensation particles at this frame (N_v(t))")};
    d.create = [] { return std::make_unique<CondensationNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
