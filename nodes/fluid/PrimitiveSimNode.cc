// PrimitiveSim: the particle fluid simulation of Sec. 4 that makes the 3D cloud primitive set.

#include <cmath>

#include "algo/fluid/PrimitiveScene.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/PrimitiveSet.h"
#include "nodes/fluid/FluidNodes.h"

namespace cg {

namespace {

algo::PrimitiveSettings settingsFrom(const ParamSet& p)
{
    algo::PrimitiveSettings s = algo::defaultPrimitiveSettings();
    s.frames = static_cast<int>(p.getInt("frames"));
    s.frameTime = p.getFloat("frameTime");
    s.width = p.getFloat("width");
    s.height = p.getFloat("height");
    s.sourceHeight = p.getFloat("sourceHeight");
    s.cloudThreshold = p.getFloat("cloudThreshold");
    s.sph.spacing = p.getFloat("spacing");
    s.sph.viscosity = p.getFloat("viscosity");
    s.sph.conduction = p.getFloat("conduction");
    s.sph.cfl = p.getFloat("cfl");
    s.sph.maxDensityError = p.getFloat("densityErrorTarget");
    s.sph.maxIterations = static_cast<int>(p.getInt("maxPressureIterations"));
    s.sph.thermo.groundTemperature = p.getFloat("groundTemperature");
    s.sph.thermo.ambientLapse = p.getFloat("ambientLapse");
    s.sph.thermo.dryLapse = p.getFloat("dryLapse");
    s.sph.thermo.ambientHumidity = p.getFloat("ambientHumidity");
    s.sph.source.radius = p.getFloat("sourceRadius");
    s.sph.source.excessTemperature = p.getFloat("sourceExcessTemperature");
    s.sph.source.humidity = p.getFloat("sourceHumidity");
    s.sph.source.relaxTime = p.getFloat("sourceRelaxTime");
    s.sph.source.duration = p.getFloat("sourceDuration");
    return s;
}

class PrimitiveSimNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        algo::PrimitiveResult r =
            algo::simulatePrimitive(settingsFrom(ctx.params()), [&ctx] { ctx.checkCancelled(); });
        ctx.setOutput("primitive", std::make_shared<PrimitiveSetData>(
                                       r.frameTime, std::move(r.counts), std::move(r.positions)));
    }
};

}  // namespace

void registerPrimitiveSimNode(Registry& registry)
{
    const algo::PrimitiveSettings def = algo::defaultPrimitiveSettings();
    NodeDecl d;
    d.type = "PrimitiveSim";
    d.version = 2;  // each version's change: CHANGES.md, "Node versions"
    d.category = "fluid";
    d.doc =
        "The 3D cloud primitive set (Sec. 4, Figure 2) by a particle fluid simulation: SPH "
        "with an implicit pressure solve (IISPH's equation by preconditioned conjugate "
        "gradients) for the incompressible "
        "Navier-Stokes equations (Eq. 1), viscosity, buoyancy as the external force, and the "
        "thermodynamics of Eq. 2 on every particle: heat conduction between neighbours "
        "(entrainment), dry adiabatic cooling -Gamma u_z, latent heat Q C_c; water vapour "
        "and condensed water per particle, saturation by Tetens' formula. Scene: still, "
        "stably stratified air in a closed box, a warm moist source near the floor feeding "
        "a rising thermal. Output: the condensed particles, ids in order of appearance, "
        "positions relative to the cloud origin (the first cloud particles' mean x, y at their "
        "lowest "
        "z), so a mapped copy grows upwards from its source particle. Frame-independent: it cooks "
        "once, cached by "
        "its key. See docs/primitive.md.";
    d.outputs = {
        port("primitive", "PrimitiveSet", "the condensed fluid particles at every frame s")};
    d.params = {
        intParam("frames", def.frames, "frames", "primitive frames s = 0..frames-1 (paper: 154)", 1,
                 100000),
        floatParam("frameTime", def.frameTime, "s",
                   "Delta s, physical time per frame; CFL sub-steps inside (value ours)", 1e-3,
                   1e4),
        floatParam("spacing", def.sph.spacing, "m", "particle spacing dx at rest (value ours)",
                   0.01, 1e5),
        floatParam("width", def.width, "m", "box edge along x and y (value ours)", 0.01, 1e7),
        floatParam("height", def.height, "m", "box height along z (value ours)", 0.01, 1e7),
        floatParam("viscosity", def.sph.viscosity, "m^2/s",
                   "mu of Eq. 1, kinematic (eddy) viscosity (value ours)", 0, 1e6),
        floatParam("conduction", def.sph.conduction, "m^2/s",
                   "alpha of Eq. 2, thermal diffusion between particles = entrainment; also mixes "
                   "vapour (value ours)",
                   0, 1e6),
        floatParam("cfl", def.sph.cfl, "", "sub-step <= cfl dx / max |u| (value ours)", 0.01, 1),
        floatParam("densityErrorTarget", def.sph.maxDensityError, "",
                   "pressure solve stops when the predicted max |rho* - rho0| / rho0 is below this "
                   "(value ours)",
                   1e-6, 0.1),
        intParam("maxPressureIterations", def.sph.maxIterations, "",
                 "pressure solve (CG) iterations at most per sub-step (value ours)", 1, 1000),
        floatParam("groundTemperature", def.sph.thermo.groundTemperature, "degC",
                   "ambient T_e at the floor (value ours)", -80, 60),
        floatParam(
            "ambientLapse", def.sph.thermo.ambientLapse, "K/m",
            "ambient -dT_e/dz; below Gamma = stably stratified (value ours: standard atmosphere)",
            0, 0.05),
        floatParam("dryLapse", def.sph.thermo.dryLapse, "K/m",
                   "Gamma of Eq. 2, dry adiabatic lapse rate", 0, 0.05),
        floatParam("ambientHumidity", def.sph.thermo.ambientHumidity, "",
                   "relative humidity of the ambient air (value ours)", 0, 1),
        floatParam("sourceHeight", def.sourceHeight, "m",
                   "source centre above the floor (value ours)", 0, 1e7),
        floatParam("sourceRadius", def.sph.source.radius, "m", "source radius (value ours)", 0,
                   1e7),
        floatParam("sourceExcessTemperature", def.sph.source.excessTemperature, "K",
                   "source air temperature above T_e (value ours)", 0, 50),
        floatParam("sourceHumidity", def.sph.source.humidity, "",
                   "relative humidity of the source air (value ours)", 0, 1),
        floatParam("sourceRelaxTime", def.sph.source.relaxTime, "s",
                   "time constant of the source heating and moistening (value ours)", 1e-3, 1e6),
        floatParam("sourceDuration", def.sph.source.duration, "s",
                   "seconds of simulated time the source stays on: a bubble rather than an "
                   "endless plume (value ours)",
                   0, 1e30),
        floatParam("cloudThreshold", def.cloudThreshold, "kg/kg",
                   "condensed water q_c that makes a fluid particle a cloud particle (value ours)",
                   0, 1),
    };
    d.validate = [](const ParamSet& p, const ParamChecker& check) {
        const double dx = p.getFloat("spacing");
        const auto nxy = static_cast<std::int64_t>(std::llround(p.getFloat("width") / dx));
        const auto nz = static_cast<std::int64_t>(std::llround(p.getFloat("height") / dx));
        if (nxy < 1 || nz < 1)
            check.fail("spacing", "the box holds less than one particle spacing");
        // Per fluid particle: state, neighbour slots and kernel gradients (about 2 KiB).
        check.checkAllocation("spacing", {nxy, nxy, nz}, 2048);
    };
    d.create = [] { return std::make_unique<PrimitiveSimNode>(); };
    d.quickParams = {{"frames", "4"},   {"width", "200"},       {"height", "200"},
                     {"spacing", "25"}, {"sourceRadius", "50"}, {"sourceHeight", "50"}};
    registry.addNode(std::move(d));
}

}  // namespace cg
