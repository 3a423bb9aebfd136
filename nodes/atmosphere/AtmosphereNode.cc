// Atmosphere: the environment of Eq. 8-9, one source of truth for the integrator and for
// condensation.

#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/atmosphere/AtmosphereNodes.h"
#include "nodes/data/AtmosphereData.h"

namespace cg {

namespace {

constexpr double kPerKm = 1e-3;  // parameters are per kilometre, the data per metre

class AtmosphereNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const ParamSet& p = ctx.params();
        Atmosphere a;
        a.groundTemperature = p.getFloat("groundTemperature");
        a.environmentLapse = p.getFloat("environmentLapseRate") * kPerKm;
        a.dewPoint = p.getFloat("dewPoint");
        a.dryLapse = p.getFloat("dryLapseRate") * kPerKm;
        a.moistLapse = p.getFloat("moistLapseRate") * kPerKm;
        a.gravity = p.getFloat("gravity");
        ctx.setOutput("atmosphere", std::make_shared<AtmosphereData>(a));
    }
};

}  // namespace

void registerAtmosphereNode(Registry& registry)
{
    NodeDecl d;
    d.type = "Atmosphere";
    d.category = "atmosphere";
    d.doc = "The environment of Sec. 5.1: ground temperature and environmental lapse rate "
            "(Eq. 9, T_e = T_sl_max - C_e z), the dew-point threshold and the particle lapse "
            "rates of Eq. 8, and gravity (Eq. 6). The defaults put the cloud base of the default "
            "VapourEmitter at 1.4 km.";
    d.outputs = {port("atmosphere", "Atmosphere", "the environment, for ThermalIntegrator and Condensation")};
    using L = AtmosphereLimits;  // the ranges a stored Atmosphere is checked against
    d.params = {
        floatParam("groundTemperature", 20.0, "degC",
                   "T_sl_max of Eq. 9: environment temperature at the ground (value ours)",
                   L::kMinTemperature, L::kMaxTemperature),
        floatParam("environmentLapseRate", 6.4, "degC/km",
                   "C_e of Eq. 9: environment cooling with height (paper: 6.4)", 0,
                   L::kMaxEnvironmentLapsePerKm),
        floatParam("dewPoint", 16.0, "degC",
                   "T_dp of Eq. 8: a particle colder than this condenses (value ours)",
                   L::kMinTemperature, L::kMaxTemperature),
        floatParam("dryLapseRate", 10.0, "degC/km",
                   "C of Eq. 8 while T_v >= T_dp: dry particle cooling (paper: 10)", 0,
                   L::kMaxParticleLapsePerKm),
        floatParam("moistLapseRate", 6.0, "degC/km",
                   "C of Eq. 8 once T_v < T_dp: moist particle cooling (paper: 6)", 0,
                   L::kMaxParticleLapsePerKm),
        floatParam("gravity", 9.81, "m/s^2", "g of Eq. 6", 0, L::kMaxGravity),
    };
    d.create = [] { return std::make_unique<AtmosphereNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
