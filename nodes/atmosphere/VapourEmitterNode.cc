// VapourEmitter: the initial water vapour particles of Sec. 5.1 (Eq. 3-5) from a density map.

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include <cmath>

#include <spdlog/spdlog.h>

#include "algo/atmosphere/Convective.h"
#include "algo/atmosphere/HeroClouds.h"
#include "algo/atmosphere/Parcel.h"
#include "algo/atmosphere/Thermodynamics.h"
#include "algo/atmosphere/VapourEmission.h"
#include "core/Error.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/atmosphere/AtmosphereNodes.h"
#include "nodes/data/AtmosphereData.h"
#include "nodes/data/Map2D.h"
#include "nodes/data/VapourParticles.h"

namespace cg {

namespace {

/// The most one emission may hold: the engine's default per-node allocation limit (16 GiB),
/// about 447 million particles, which also keeps every id within a PLY int.
constexpr std::uint64_t kMaxEmissionBytes = std::uint64_t(16) << 30;
constexpr std::uint64_t kMaxParticles = kMaxEmissionBytes / algo::kVapourParticleBytes;

algo::VapourEmissionSettings settingsFrom(const ParamSet& p)
{
    algo::VapourEmissionSettings s;
    s.minParticlesPerCell = p.getFloat("minParticlesPerCell");
    s.maxParticlesPerCell = p.getFloat("maxParticlesPerCell");
    s.minHeight = p.getFloat("minHeight");
    s.maxHeight = p.getFloat("maxHeight");
    s.minTemperature = p.getFloat("minTemperature");
    s.maxTemperature = p.getFloat("maxTemperature");
    s.seed = static_cast<std::uint64_t>(p.getInt("seed"));
    return s;
}

/// Ours: amplitude (2 m - 1) for each particle, m the moisture map's value at its x, y (the
/// map clamped at its edges), so a map in [0, 1] perturbs dew points by up to +-amplitude.
std::vector<float> dewpointOffsets(const Map2DData& moisture, const VapourStatics& s,
                                   double amplitude)
{
    std::vector<float> offsets(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) {
        const double m = moisture.values[static_cast<std::size_t>(moisture.cellAt(s.x[i], s.y[i]))];
        offsets[i] = static_cast<float>(amplitude * (2.0 * m - 1.0));
    }
    return offsets;
}

/// Convective inhibition (J/kg) a thermal starting at rest is taken to cross (ours).
constexpr double kCinTolerance = 1.0;

/// How a thermal starts against the air it rises from (ours): its temperature and dew point
/// at the ground, and by how much each particle's start differs from the air at its height.
struct ThermalStart {
    double groundC = 0.0, groundDewpointC = 0.0;
    bool convective = false;
};

/// With start 'excess' or 'convective': every particle's temperature from the profile, and
/// its dew point as an offset from the profile's at its start height (what the thermal
/// integrator reads), added to any from the moisture map. Warns when such a thermal reaches
/// no level of free convection.
void startFromProfile(CookContext& ctx, VapourStatics& statics, std::vector<float>& temperature)
{
    const ParamSet& p = ctx.params();
    const auto atmosphereData = ctx.input<AtmosphereData>("atmosphere");
    if (!atmosphereData || !atmosphereData->atmosphere.profile)
        throw InputError(ctx.nodeId() + "/inputs/atmosphere",
                         "start '" + p.getString("start") +
                             "' needs an atmosphere with a profile (a sounding or the "
                             "standard atmosphere) to start the vapour relative to its air");
    const algo::EnvironmentProfile& profile = *atmosphereData->atmosphere.profile;
    const double excess = p.getFloat("temperatureExcess");
    const double moisture = p.getFloat("moistureExcess");
    const double ground = profile.groundHeight();
    ThermalStart start{profile.temperature(ground), profile.dewpoint(ground),
                       p.getString("start") == "convective"};
    if (start.convective) {
        algo::ConvectiveLevels levels;
        try {
            levels = algo::convectiveLevels(profile);
        } catch (const std::invalid_argument& e) {
            throw InputError(ctx.nodeId() + "/inputs/atmosphere", e.what());
        }
        start.groundC = levels.convectiveTemperatureC;
        spdlog::info(
            "{}: convective temperature {:.1f} C, convective condensation level {:.0f} m "
            "above the ground",
            ctx.nodeId(), levels.convectiveTemperatureC, levels.cclM - ground);
    }
    if (statics.dewpointOffset.empty()) statics.dewpointOffset.assign(statics.size(), 0.0f);
    for (std::size_t i = 0; i < statics.size(); ++i) {
        const double z0 = statics.startZ[i];
        const double air = profile.temperature(ground + z0);
        // Convective: surface air heated to T_c, risen dry to z0, its mixing ratio kept.
        const double t =
            start.convective ? start.groundC - algo::thermo::kDryAdiabaticLapse * z0 : air;
        const double dewpoint =
            start.convective ? start.groundDewpointC - algo::thermo::kParcelDewpointLapse * z0
                             : profile.dewpoint(ground + z0);
        temperature[i] = static_cast<float>(t + excess);
        statics.dewpointOffset[i] +=
            static_cast<float>(dewpoint + moisture - profile.dewpoint(ground + z0));
    }
    const algo::ParcelAscent thermal =
        algo::liftParcel(profile, ground, start.groundC + excess, start.groundDewpointC + moisture);
    // Particles start at rest: any layer of negative buoyancy below the LFC stops them.
    if (std::isnan(thermal.lfcM) || thermal.cinJPerKg < -kCinTolerance)
        spdlog::warn(
            "{}: a thermal starting {:.1f} C, dew point {:.1f} C, at the ground reaches "
            "no level of free convection on its own (CIN {:.0f} J/kg{}): clouds stay "
            "shallow or do not form; start 'convective' or a larger temperatureExcess "
            "lifts them",
            ctx.nodeId(), start.groundC + excess, start.groundDewpointC + moisture,
            thermal.cinJPerKg, std::isnan(thermal.lfcM) ? ", no LFC at all" : "");
}

/// Ours: each particle's start delay, startDelayMax times the startDelay map's value at its
/// x, y (a cloud starts when its ground says); empty without the map or with no delay.
std::vector<float> startDelays(const CookContext& ctx, const VapourStatics& s)
{
    const auto delayMap = ctx.input<Map2DData>("startDelay");
    const double most = ctx.params().getFloat("startDelayMax");
    if (!delayMap || !(most > 0.0)) return {};
    std::vector<float> delays(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) {
        const float m =
            delayMap->values[static_cast<std::size_t>(delayMap->cellAt(s.x[i], s.y[i]))];
        if (!(m >= 0.0f && m <= 1.0f))
            throw InputError(
                ctx.nodeId() + "/inputs/startDelay",
                "the start delay map's values must be in [0, 1], got " + std::to_string(m));
        delays[i] = static_cast<float>(most * m);
    }
    return delays;
}

/// When each particle leaves its start: over emissionDuration after its delay (ours), its hero
/// cloud's start standing for the delay when its cell is a hero's. No release times when all
/// leave at t0.
void setReleaseTimes(VapourStatics& statics, double duration, std::uint64_t seed,
                     const std::vector<algo::HeroCloud>& heroes,
                     const std::vector<std::int32_t>& heroOf, const std::vector<float>& delays)
{
    bool late = duration > 0.0 || !delays.empty();
    for (const algo::HeroCloud& h : heroes) late = late || h.start > 0.0;
    if (!late) return;
    statics.releaseTime.resize(statics.size());
    for (std::size_t i = 0; i < statics.size(); ++i) {
        const float spread =
            duration > 0.0 ? algo::releaseTime(seed, statics.id[i], duration) : 0.0f;
        const std::int32_t hero = heroOf[statics.homeCell[i]];
        const float delay = hero >= 0
                                ? static_cast<float>(heroes[static_cast<std::size_t>(hero)].start)
                            : delays.empty() ? 0.0f
                                             : delays[i];
        statics.releaseTime[i] = delay + spread;
    }
}

class VapourEmitterNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto input = ctx.input<Map2DData>("map");
        const algo::VapourEmissionSettings s = settingsFrom(ctx.params());
        // The map the vapour rises from: the input raised by the hero clouds.
        std::vector<float> values = input->values;
        const std::vector<algo::HeroCloud> heroes =
            algo::heroCloudsFromList(ctx.params().getFloatList("heroClouds"));
        const std::vector<std::int32_t> heroOf =
            algo::stampHeroClouds(input->nx, input->ny, input->cellSize, values, heroes);
        const auto map =
            std::make_shared<Map2DData>(input->nx, input->ny, input->cellSize, std::move(values));

        // Refuse before allocating: the count depends on the map, so load time cannot know it.
        const std::uint64_t count = algo::emissionCount(map->values, s);
        if (count > kMaxParticles) {
            throw InputError(ctx.nodeId(),
                             "parameter 'maxParticlesPerCell' makes " + std::to_string(count) +
                                 " particles over the " + std::to_string(map->nx) + " x " +
                                 std::to_string(map->ny) + " map, over the limit of " +
                                 std::to_string(kMaxParticles) + " (" +
                                 std::to_string(kMaxEmissionBytes >> 30) + " GiB)");
        }

        algo::VapourEmission e;
        try {
            e = algo::emitVapour(map->nx, map->ny, map->cellSize, map->values, s,
                                 [&ctx] { ctx.checkCancelled(); });
        } catch (const std::invalid_argument& err) {
            throw InputError(ctx.nodeId(), std::string("input 'map': ") + err.what());
        }

        auto statics = std::make_shared<VapourStatics>();
        statics->id = std::move(e.id);
        statics->homeCell = std::move(e.homeCell);
        statics->x = std::move(e.x);
        statics->y = std::move(e.y);
        statics->startZ = e.z;
        setReleaseTimes(*statics, ctx.params().getFloat("emissionDuration"), s.seed, heroes, heroOf,
                        startDelays(ctx, *statics));
        if (const auto moisture = ctx.input<Map2DData>("moisture")) {
            const double amplitude = ctx.params().getFloat("moistureAmplitude");
            if (amplitude > 0.0)
                statics->dewpointOffset = dewpointOffsets(*moisture, *statics, amplitude);
        }
        if (ctx.params().getString("start") != "paper")
            startFromProfile(ctx, *statics, e.temperature);
        ctx.setOutput("particles", std::make_shared<VapourParticlesData>(
                                       std::move(statics), std::move(e.z), std::move(e.vz),
                                       std::move(e.temperature)));
        ctx.setOutput("map", map);
    }
};

}  // namespace

void registerVapourEmitterNode(Registry& registry)
{
    NodeDecl d;
    d.type = "VapourEmitter";
    d.version = 5;
    d.category = "atmosphere";
    d.doc =
        "Initial water vapour particles of the stochastic simulation (Sec. 5.1) at time t0. "
        "Map cell (ix, iy) with density fNoise in [0, 1] emits floor(W_p + 0.5) particles "
        "(Eq. 3, rounded half up), W_p = W_p_min + (W_p_max - W_p_min) fNoise; each starts at "
        "rest at height P_vz = P_vz_min + (P_vz_max - P_vz_min) fNoise (Eq. 4) with "
        "temperature T_v = T_v_max - (T_v_max - T_v_min) (P_vz - P_vz_min) / (P_vz_max - "
        "P_vz_min) (Eq. 5; T_v_max when the heights are equal), at a uniform random x, y "
        "inside the cell keyed by (seed, cell, particle), so the result is the same for any "
        "thread count. Ids are 0..N-1 in row-major cell order. The defaults make (T_v_max - "
        "T_v_min) / (P_vz_max - P_vz_min) equal the dry lapse rate of 10 degC/km with which "
        "vapour cools as it rises (Eq. 8), so every particle reaches the dew point at the same "
        "altitude and the cloud base is flat. The emission does not change with the frame: "
        "ThermalIntegrator takes it as its start state. A map density outside [0, 1], or more "
        "than 16 GiB of particles (about 447 million), is refused. Ours (docs/atmosphere.md): an "
        "optional moisture map "
        "perturbs each "
        "particle's dew point by moistureAmplitude (2 m - 1) C, m the map's value at the "
        "particle, so the cloud base is irregular (the paper's Sec. 7 asks for it); no map or "
        "amplitude 0 gives the paper's flat base. Also ours: with emissionDuration > 0 each "
        "particle waits at its start "
        "until a release time drawn uniformly from [0, emissionDuration) s keyed by (seed, "
        "id), so a source keeps feeding its tower, as a real updraft does, instead of "
        "rising as one bubble; a startDelay map delays that window by startDelayMax times "
        "its value under the particle, so clouds start at different times where it says "
        "(a hero cloud's start replaces it). Also ours: start 'excess' or 'convective' (with the "
        "atmosphere input's profile) replaces Eq. 5: each particle starts temperatureExcess "
        "warmer than the air at its height, or than surface air heated to the sounding's "
        "convective temperature T_c and risen dry (its mixing ratio kept), so any afternoon "
        "sounding makes cumulus with bases near its convective condensation level; a thermal "
        "that reaches no level of free convection is reported in the log with its CIN.";
    d.inputs = {
        port("map", "Map2D", "the 1/f^beta density map fNoise(ix, iy) of Eq. 3-5, in [0, 1]"),
        port("moisture", "Map2D",
             "ours, optional: a second map in [0, 1] that perturbs each particle's dew point "
             "(irregular cloud bases)",
             true),
        port("startDelay", "Map2D",
             "ours, optional: a map in [0, 1] that delays each particle's release by "
             "startDelayMax times its value there (clouds that start at different times)",
             true),
        port("atmosphere", "Atmosphere",
             "ours, for start 'excess' and 'convective': the profile the vapour starts against",
             true)};
    d.outputs = {port("particles", "VapourParticles",
                      "the vapour particles at t0: position, U_vz = 0 and T_v"),
                 port("map", "Map2D",
                      "the map the vapour rose from: the input raised by the hero clouds (wire "
                      "it to PrimitiveMapper's map, so a hero's copies get Eq. 16's full scale)")};
    d.params = {
        floatParam("minParticlesPerCell", 0.0, "particles",
                   "W_p_min of Eq. 3: particles of a cell with density 0 (value ours)", 0.0, 1e6),
        floatParam("maxParticlesPerCell", 6.0, "particles",
                   "W_p_max of Eq. 3: particles of a cell with density 1 (value ours)", 0.0, 1e6),
        floatParam("minHeight", 0.0, "m",
                   "P_vz_min of Eq. 4: initial height at density 0 (value ours)", 0.0, 1e5),
        floatParam("maxHeight", 100.0, "m",
                   "P_vz_max of Eq. 4: initial height at density 1 (value ours)", 0.0, 1e5),
        floatParam("minTemperature", 29.0, "degC",
                   "T_v_min of Eq. 5: initial temperature at maxHeight (value ours)", -100.0,
                   100.0),
        floatParam("maxTemperature", 30.0, "degC",
                   "T_v_max of Eq. 5: initial temperature at minHeight (value ours)", -100.0,
                   100.0),
        intParam("seed", 0, "", "keys the random x, y inside each cell (value ours)", 0.0,
                 9007199254740992.0),
        floatParam("moistureAmplitude", 0.0, "degC",
                   "ours: the largest dew-point perturbation the moisture map gives (0: the "
                   "paper's flat base)",
                   0.0, 20.0),
        floatListParam("heroClouds", {}, "",
                       "ours: thermals placed by the layout, 4 numbers each: x, y, radius (m) "
                       "and start (s after the first frame); a hero's cells take density 1 "
                       "within half its radius, smoothly 0 at its radius, above the map's own, "
                       "and their vapour waits until the start"),
        floatParam("emissionDuration", 0.0, "s",
                   "ours: particles leave their start at random times over this long (0: all "
                   "at t0, the paper's)",
                   0.0, 1e6),
        floatParam("startDelayMax", 0.0, "s",
                   "ours: the release delay where the startDelay map is 1 (0: no delay)", 0.0, 1e6),
        stringParam("start", "paper",
                    "how vapour starts: paper = Eq. 5's temperatures; excess (ours) = the "
                    "profile's air at the start height plus temperatureExcess, its dew point "
                    "plus moistureExcess; convective (ours) = surface air heated to the "
                    "sounding's convective temperature and risen dry to the start height, plus "
                    "the excesses, so bases form at the convective condensation level",
                    {"paper", "excess", "convective"}),
        floatParam("temperatureExcess", 0.5, "degC",
                   "excess and convective: how much warmer than that air a thermal starts "
                   "(a few tenths to a few C in real thermals; value ours)",
                   -10.0, 10.0),
        floatParam("moistureExcess", 0.0, "degC",
                   "excess and convective: how much higher its dew point starts (value ours)",
                   -20.0, 20.0)};
    d.validate = [](const ParamSet& p, const ParamChecker& check) {
        try {
            algo::heroCloudsFromList(p.getFloatList("heroClouds"));
        } catch (const std::invalid_argument& e) {
            check.fail("heroClouds", e.what());
        }
        // Each pair must be an ordered range, or Eq. 3-5 run backwards.
        if (p.getFloat("maxParticlesPerCell") < p.getFloat("minParticlesPerCell"))
            check.fail("maxParticlesPerCell",
                       "maxParticlesPerCell (" + std::to_string(p.getFloat("maxParticlesPerCell")) +
                           ") is below minParticlesPerCell (" +
                           std::to_string(p.getFloat("minParticlesPerCell")) + ")");
        if (p.getFloat("maxHeight") < p.getFloat("minHeight"))
            check.fail("maxHeight", "maxHeight (" + std::to_string(p.getFloat("maxHeight")) +
                                        " m) is below minHeight (" +
                                        std::to_string(p.getFloat("minHeight")) + " m)");
        if (p.getFloat("maxTemperature") < p.getFloat("minTemperature"))
            check.fail("maxTemperature",
                       "maxTemperature (" + std::to_string(p.getFloat("maxTemperature")) +
                           " degC) is below minTemperature (" +
                           std::to_string(p.getFloat("minTemperature")) + " degC)");
    };
    d.create = [] { return std::make_unique<VapourEmitterNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
