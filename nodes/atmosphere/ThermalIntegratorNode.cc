// ThermalIntegrator: vapour particles rising under buoyancy (Eq. 6-9), stepped frame by frame.

#include "algo/atmosphere/Thermal.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/atmosphere/AtmosphereNodes.h"
#include "nodes/data/AtmosphereData.h"
#include "nodes/data/VapourParticles.h"

namespace cg {

namespace {

algo::ThermalSettings settingsFrom(const CookContext& ctx, const Atmosphere& a)
{
    algo::ThermalSettings s;
    s.buoyancyCoefficient = ctx.params().getFloat("buoyancyCoefficient");
    s.mass = ctx.params().getFloat("particleMass");
    s.groundStops = ctx.params().getBool("groundStopsParticles");
    s.gravity = a.gravity;
    s.groundTemperature = a.groundTemperature;
    s.environmentLapse = a.environmentLapse;
    s.dewPoint = a.dewPoint;
    s.dryLapse = a.dryLapse;
    s.moistLapse = a.moistLapse;
    s.timeStep = ctx.timeStep();
    return s;
}

class ThermalIntegratorNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto emitted = ctx.input<VapourParticlesData>("particles");
        const auto previous = ctx.previous<VapourParticlesData>("particles");
        if (!previous) {
            ctx.setOutput("particles", emitted);  // t = t0: the emission itself
            return;
        }
        const auto atmosphere = ctx.input<AtmosphereData>("atmosphere");
        const std::size_t n = previous->size();
        std::vector<float> z(n), vz(n), temperature(n);
        algo::thermalStepParallel(settingsFrom(ctx, atmosphere->atmosphere),
                                  {previous->z.data(), previous->vz.data(), previous->temperature.data()},
                                  {z.data(), vz.data(), temperature.data()}, n,
                                  [&ctx] { ctx.checkCancelled(); });
        ctx.setOutput("particles",
                      std::make_shared<VapourParticlesData>(previous->statics, std::move(z),
                                                            std::move(vz), std::move(temperature)));
    }
};

}  // namespace

void registerThermalIntegratorNode(Registry& registry)
{
    NodeDecl d;
    d.type = "ThermalIntegrator";
    d.category = "atmosphere";
    d.doc = "Vapour particles rising under the thermal effect (Sec. 5.1, pseudocode lines 29-35). "
            "On the start frame (t0) the particles are the emitted ones; each later frame is "
            "one explicit Euler step of the graph's timeStep (Delta t) from the previous frame: "
            "T_e = T_sl_max - C_e z (Eq. 9), f = C_b (T_v - T_e) - m g (Eq. 6, vertical only), "
            "U += dt f / m and P += dt U(t) (Eq. 7, position advanced with the old velocity), "
            "T_v -= C dz with C = 10 C/km while T_v >= T_dp and 6 C/km after (Eq. 8). "
            "Interaction between particles and wind are ignored, as in the paper.";
    d.simulation = true;
    d.readsTimeStep = true;
    d.inputs = {port("particles", "VapourParticles", "the emitted vapour particles at t0"),
                port("atmosphere", "Atmosphere", "the environment (Eq. 8-9)")};
    d.outputs = {port("particles", "VapourParticles", "the particles at this frame")};
    d.params = {
        floatParam("buoyancyCoefficient", 2.0, "N/degC",
                   "C_b of Eq. 6 (value ours: with m = 1 kg, particles stay buoyant up to the "
                   "default 1.4 km cloud base and keep rising above it)", 0, 1e6),
        floatParam("particleMass", 1.0, "kg", "m of Eq. 6-7 (value ours)", 1e-9, 1e9),
        boolParam("groundStopsParticles", true,
                  "ours, not the paper's: a particle cannot sink below the ground z = 0"),
    };
    d.create = [] { return std::make_unique<ThermalIntegratorNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
