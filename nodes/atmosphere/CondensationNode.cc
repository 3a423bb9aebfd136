// Condensation: vapour particles colder than the dew point become condensation particles
// (pseudocode lines 9-14); records when each condensed and when the first one did.

#include <optional>

#include "algo/atmosphere/ColumnThermal.h"
#include "algo/atmosphere/Condensation.h"
#include "core/CoreData.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/atmosphere/AtmosphereNodes.h"
#include "nodes/data/AtmosphereData.h"
#include "nodes/data/VapourParticles.h"

namespace cg {

namespace {

/// Each particle's own dew point now: from the profile at its start height, less
/// 1.8 C/km risen, or the paper's T_dp; plus its offset.
std::vector<float> particleDewpoints(const AtmosphereData& a, const VapourParticlesData& particles)
{
    const VapourStatics& st = *particles.statics;
    algo::ParticleStart m;
    m.startZ = st.startZ.data();
    m.dewpointOffset = st.dewpointOffset.empty() ? nullptr : st.dewpointOffset.data();
    std::vector<float> dewpoints(particles.size());
    for (std::size_t i = 0; i < dewpoints.size(); ++i)
        dewpoints[i] =
            algo::particleDewpoint(a.column, a.atmosphere.dewPoint, m, i, particles.z[i]);
    return dewpoints;
}

class CondensationNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto particles = ctx.input<VapourParticlesData>("particles");
        const auto data = ctx.input<AtmosphereData>("atmosphere");
        const Atmosphere& atmosphere = data->atmosphere;
        const auto previous = ctx.previous<CondensationData>("condensation");
        std::optional<algo::CondensationState> before;
        if (previous)
            before = algo::CondensationState{previous->condensedFrame, previous->condensedHeight,
                                             previous->firstFrame, 0};
        algo::CondensationState now;
        const auto frame = static_cast<std::int32_t>(ctx.frame());
        if (atmosphere.profile || !particles->statics->dewpointOffset.empty()) {
            const std::vector<float> dewpoints = particleDewpoints(*data, *particles);
            now =
                algo::condenseStep(before ? &*before : nullptr, particles->temperature.data(),
                                   dewpoints.data(), particles->z.data(), particles->size(), frame);
        } else {
            now = algo::condenseStep(before ? &*before : nullptr, particles->temperature.data(),
                                     particles->z.data(), particles->size(), atmosphere.dewPoint,
                                     frame);
        }
        ctx.setOutput("firstFrame", std::make_shared<IntData>(now.firstFrame));
        ctx.setOutput("count", std::make_shared<IntData>(static_cast<std::int64_t>(now.count)));
        ctx.setOutput("condensation", std::make_shared<CondensationData>(
                                          particles, std::move(now.condensedFrame),
                                          std::move(now.condensedHeight), now.firstFrame));
    }
};

}  // namespace

void registerCondensationNode(Registry& registry)
{
    NodeDecl d;
    d.type = "Condensation";
    d.category = "atmosphere";
    d.doc =
        "Marks vapour particles whose temperature T_v has fallen below the dew point T_dp as "
        "condensation particles (pseudocode lines 9-14) and remembers the frame at which each "
        "condensed and its height then (its condensation level); once condensed, a particle "
        "stays a condensation particle. Also gives the frame at which the first condensation "
        "particle appeared: t_s[1] of Sec. 5.2. A "
        "simulation: each frame builds on the previous one. Ours (docs/atmosphere.md): with an "
        "Atmosphere profile each particle has its own dew point, the profile's at its start "
        "height falling 1.8 degC/km as it rises, so it condenses at its lifting condensation "
        "level; a VapourEmitter moisture map adds each particle's perturbation.";
    d.version = 3;  // each version's change: CHANGES.md, "Node versions"
    d.simulation = true;
    d.inputs = {port("particles", "VapourParticles", "the particles at this frame"),
                port("atmosphere", "Atmosphere", "the environment (its dew point T_dp)")};
    d.outputs = {
        port("condensation", "Condensation", "the particles with their condensation frames"),
        port("firstFrame", "Int", "frame of the first condensation (t_s[1]); -1 if none yet"),
        port("count", "Int", "number of condensation particles at this frame (N_v(t))")};
    d.create = [] { return std::make_unique<CondensationNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
