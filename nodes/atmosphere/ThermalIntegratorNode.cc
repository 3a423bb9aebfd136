// ThermalIntegrator: vapour particles rising under buoyancy (Eq. 6-9), stepped frame by frame;
// with a real atmosphere, through a profile, with wind and outflow.

#include <cmath>

#include "algo/atmosphere/ColumnThermal.h"
#include "algo/atmosphere/Outflow.h"
#include "algo/atmosphere/Parcel.h"
#include "algo/atmosphere/Thermal.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/atmosphere/AtmosphereNodes.h"
#include "nodes/data/AtmosphereData.h"
#include "nodes/data/VapourParticles.h"

namespace cg {

namespace {

/// Ours: towers are told apart on ground cells this large (docs/atmosphere.md, "Anvils").
constexpr double kTowerCellSize = 500.0;

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

/// Where the outflow may start: the level of free convection of a parcel lifted from the
/// profile's ground (its LCL when it has none); the ground without a profile.
double outflowBottom(const Atmosphere& a)
{
    if (!a.profile) return 0.0;
    const algo::ParcelAscent p = algo::liftParcel(*a.profile, a.profile->groundHeight());
    return (std::isnan(p.lfcM) ? p.lclM : p.lfcM) - a.profile->groundHeight();
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
        const auto data = ctx.input<AtmosphereData>("atmosphere");
        const Atmosphere& atmosphere = data->atmosphere;
        const algo::ThermalSettings paper = settingsFrom(ctx, atmosphere);
        const ParamSet& p = ctx.params();
        const bool beyondPaper =
            atmosphere.beyondPaper() || p.getString("buoyancy") != "paper" ||
            p.getFloat("drag") > 0.0 || p.getFloat("outflowDivergence") > 0.0 ||
            !previous->statics->dewpointOffset.empty() || !previous->statics->releaseTime.empty() ||
            previous->movedHorizontally();
        ctx.setOutput("particles", beyondPaper ? stepThroughColumn(ctx, paper, *data, *previous)
                                               : stepAsPaper(ctx, paper, *previous));
    }

private:
    /// The paper's Eq. 6-9 exactly; x, y stay the emission's.
    static std::shared_ptr<VapourParticlesData> stepAsPaper(CookContext& ctx,
                                                            const algo::ThermalSettings& s,
                                                            const VapourParticlesData& previous)
    {
        const std::size_t n = previous.size();
        std::vector<float> z(n), vz(n), temperature(n);
        algo::thermalStepParallel(
            s, {previous.z.data(), previous.vz.data(), previous.temperature.data()},
            {z.data(), vz.data(), temperature.data()}, n, [&ctx] { ctx.checkCancelled(); });
        return std::make_shared<VapourParticlesData>(previous.statics, std::move(z), std::move(vz),
                                                     std::move(temperature));
    }

    static std::shared_ptr<VapourParticlesData> stepThroughColumn(
        CookContext& ctx, const algo::ThermalSettings& paper, const AtmosphereData& data,
        const VapourParticlesData& previous)
    {
        const ParamSet& p = ctx.params();
        const Atmosphere& atmosphere = data.atmosphere;
        algo::ColumnThermalSettings s;
        s.paper = paper;
        s.buoyancy =
            p.getString("buoyancy") == "parcel" ? algo::Buoyancy::Parcel : algo::Buoyancy::Paper;
        s.drag = p.getFloat("drag");
        s.column = &data.column;
        s.moistAdiabat = atmosphere.moistAdiabat;
        s.outflowDivergence = p.getFloat("outflowDivergence");
        s.outflowMaxSpeed = p.getFloat("outflowMaxSpeed");
        s.time = (ctx.frame() - 1 - ctx.startFrame()) * paper.timeStep;  // the previous frame's

        const VapourStatics& st = *previous.statics;
        const std::size_t n = previous.size();
        const std::vector<float>& x = previous.xs();
        const std::vector<float>& y = previous.ys();
        std::vector<float> axisX, axisY;
        if (s.outflowDivergence > 0.0) {
            s.outflowBottom = outflowBottom(atmosphere);
            algo::towerAxes(algo::towerIds(st.x.data(), st.y.data(), n, kTowerCellSize), x.data(),
                            y.data(), previous.z.data(), static_cast<float>(s.outflowBottom), axisX,
                            axisY);
        }
        std::vector<float> xNext(n), yNext(n), vxNext(n), vyNext(n), z(n), vz(n), temperature(n);
        const auto orNull = [](const std::vector<float>& v) {
            return v.empty() ? nullptr : v.data();
        };
        algo::columnThermalStepParallel(
            s, {st.startZ.data(), orNull(st.dewpointOffset), orNull(st.releaseTime)},
            {orNull(axisX), orNull(axisY)},
            {x.data(), y.data(), previous.z.data(), previous.vz.data(),
             previous.temperature.data()},
            {xNext.data(), yNext.data(), z.data(), vz.data(), temperature.data(), vxNext.data(),
             vyNext.data()},
            n, [&ctx] { ctx.checkCancelled(); });
        // Particles nothing moves sideways keep sharing the emission's x, y.
        if (atmosphere.wind.calm() && s.outflowDivergence <= 0.0 && !previous.movedHorizontally()) {
            xNext.clear();
            yNext.clear();
            vxNext.clear();
            vyNext.clear();
        }
        return std::make_shared<VapourParticlesData>(
            previous.statics, std::move(xNext), std::move(yNext), std::move(vxNext),
            std::move(vyNext), std::move(z), std::move(vz), std::move(temperature));
    }
};

}  // namespace

void registerThermalIntegratorNode(Registry& registry)
{
    NodeDecl d;
    d.type = "ThermalIntegrator";
    d.version = 3;  // each version's change: CHANGES.md, "Node versions"
    d.category = "atmosphere";
    d.doc =
        "Vapour particles rising under the thermal effect (Sec. 5.1, pseudocode lines 29-35). "
        "On the start frame (t0) the particles are the emitted ones; each later frame is "
        "one explicit Euler step of the graph's timeStep (Delta t) from the previous frame: "
        "T_e = T_sl_max - C_e z (Eq. 9), f = C_b (T_v - T_e) - m g (Eq. 6, vertical only), "
        "U += dt f / m and P += dt U(t) (Eq. 7, position advanced with the old velocity), "
        "T_v -= C dz with C = 10 C/km while T_v >= T_dp and 6 C/km after (Eq. 8). With the "
        "paper's atmosphere and the defaults below this is the paper's step exactly, and x, y "
        "never change. Ours (docs/atmosphere.md): with an Atmosphere profile, T_e "
        "is the profile's, each particle condenses at its own lifting condensation level "
        "and, saturated, cools at the moist adiabatic rate; a wind moves x, y by the wind at "
        "the particle's height; 'parcel' buoyancy, drag and the outflow at the top of a "
        "tower (anvils) are below.";
    d.simulation = true;
    d.readsTimeStep = true;
    d.inputs = {port("particles", "VapourParticles", "the emitted vapour particles at t0"),
                port("atmosphere", "Atmosphere", "the environment (Eq. 8-9)")};
    d.outputs = {port("particles", "VapourParticles", "the particles at this frame")};
    d.params = {
        floatParam("buoyancyCoefficient", 2.0, "N/degC",
                   "C_b of Eq. 6 (value ours: with m = 1 kg, particles stay buoyant up to the "
                   "default 1.4 km cloud base and keep rising above it)",
                   0, 1e6),
        floatParam("particleMass", 1.0, "kg", "m of Eq. 6-7 (value ours)", 1e-9, 1e9),
        boolParam("groundStopsParticles", true,
                  "ours, not the paper's: a particle cannot sink below the ground z = 0"),
        stringParam("buoyancy", "paper",
                    "'paper': Eq. 6, f = C_b (T_v - T_e) - m g, neutral where T_v - T_e = m g / "
                    "C_b; 'parcel' (ours): f / m = g (T_v - T_e) / T_e in kelvin, neutral where "
                    "T_v = T_e, so towers stop at the profile's equilibrium level",
                    {"paper", "parcel"}),
        floatParam("drag", 0.0, "1/m",
                   "ours: quadratic drag, f / m -= drag |U| U, the mixing that keeps updrafts "
                   "near 10-30 m/s and overshooting tops short (0: none, the paper's)",
                   0.0, 1.0),
        floatParam("outflowDivergence", 0.0, "1/s",
                   "ours: saturated particles colder than the environment above the level of "
                   "free convection (the top of a tower) move away from their tower's axis at "
                   "this rate times their distance from it: the anvil (0: none, the paper's)",
                   0.0, 1.0),
        floatParam("outflowMaxSpeed", 0.0, "m/s",
                   "ours: the outflow moves a particle at most this fast, as an anvil spreads "
                   "as a gravity current of 10-20 m/s rather than ever faster with its size "
                   "(0: no cap)",
                   0.0, 200.0),
    };
    d.create = [] { return std::make_unique<ThermalIntegratorNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
