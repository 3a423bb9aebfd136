// Atmosphere: the environment of Eq. 8-9, one source of truth for the integrator and for
// condensation; optionally a sounding or the standard atmosphere, and wind.

#include <stdexcept>
#include <string>

#include "core/Hash.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "formats/FormatError.h"
#include "formats/Sounding.h"
#include "nodes/DeclHelpers.h"
#include "nodes/atmosphere/AtmosphereNodes.h"
#include "nodes/atmosphere/SoundingProfile.h"
#include "nodes/data/AtmosphereData.h"

namespace cg {

namespace {

constexpr double kPerKm = 1e-3;  // parameters are per kilometre, the data per metre
/// Ours: the standard atmosphere reaches this high, above any tropopause the node allows.
constexpr double kStandardTop = 20000.0;

/// The sounding the parameters name, as a profile; a bad file is bad input. `what` says which
/// node asks, for the message.
std::shared_ptr<const algo::EnvironmentProfile> soundingProfile(const ParamSet& p)
{
    const std::string& file = p.getString("soundingFile");
    if (file.empty()) throw std::invalid_argument("parameter 'soundingFile' is empty");
    const formats::Sounding sounding = formats::readSounding(file);
    auto profile = std::make_shared<const algo::EnvironmentProfile>(profileFromSounding(sounding));
    if (profile->topHeight() - profile->groundHeight() > AtmosphereLimits::kMaxProfileDepth)
        throw formats::FormatError(file, "the sounding is deeper than 100 km");
    return profile;
}

std::shared_ptr<const algo::EnvironmentProfile> profileFrom(const ParamSet& p)
{
    const std::string& kind = p.getString("profile");
    if (kind == "sounding") return soundingProfile(p);
    if (kind == "standard")
        return std::make_shared<const algo::EnvironmentProfile>(algo::standardAtmosphere(
            p.getFloat("surfaceTemperature"), p.getFloat("surfaceDewPoint"),
            p.getFloat("tropopauseHeight"), kStandardTop));
    return nullptr;  // linear: the paper's Eq. 9
}

/// The wind the parameters ask for, seen from the ground; heights above the ground.
algo::WindProfile groundWindFrom(const ParamSet& p, const algo::EnvironmentProfile* profile)
{
    const std::string& kind = p.getString("wind");
    if (kind == "layers")
        return algo::WindProfile::fromSpeedAndDirection(p.getFloatList("windHeights"),
                                                        p.getFloatList("windSpeeds"),
                                                        p.getFloatList("windDirections"));
    if (kind == "sounding" && profile) {
        std::vector<algo::WindLevel> levels;
        for (const algo::ProfileLevel& l : profile->levels())
            levels.push_back({l.heightM - profile->groundHeight(), l.windEastMs, l.windNorthMs});
        return algo::WindProfile(std::move(levels));
    }
    return {};
}

/// The wind in the frame the parameters ask for: the ground's, or the storm's (minus the mean
/// wind below steeringDepth), so a tower or field fed from a fixed patch of ground moves as
/// one carried by the mean wind does, and only the shear around that mean tilts it.
algo::WindProfile windFrom(const ParamSet& p, const algo::EnvironmentProfile* profile)
{
    const algo::WindProfile ground = groundWindFrom(p, profile);
    if (p.getString("windFrame") != "storm") return ground;
    return ground.relativeTo(ground.meanBelow(p.getFloat("steeringDepth")));
}

Atmosphere atmosphereFrom(const ParamSet& p)
{
    Atmosphere a;
    a.groundTemperature = p.getFloat("groundTemperature");
    a.environmentLapse = p.getFloat("environmentLapseRate") * kPerKm;
    a.dewPoint = p.getFloat("dewPoint");
    a.dryLapse = p.getFloat("dryLapseRate") * kPerKm;
    a.moistLapse = p.getFloat("moistLapseRate") * kPerKm;
    a.gravity = p.getFloat("gravity");
    a.profile = profileFrom(p);
    a.moistAdiabat = p.getBool("moistAdiabat");
    a.wind = windFrom(p, a.profile.get());
    return a;
}

class AtmosphereNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        ctx.setOutput("atmosphere", std::make_shared<AtmosphereData>(atmosphereFrom(ctx.params())));
    }
};

void validate(const ParamSet& p, const ParamChecker& check)
{
    const std::string& profile = p.getString("profile");
    if (profile == "sounding") {
        try {
            soundingProfile(p);
        } catch (const std::exception& e) {
            check.fail("soundingFile", e.what());
        }
    }
    if (profile == "standard" && p.getFloat("surfaceDewPoint") > p.getFloat("surfaceTemperature"))
        check.fail("surfaceDewPoint", "is above surfaceTemperature");
    const std::string& wind = p.getString("wind");
    if (wind == "sounding" && profile != "sounding")
        check.fail("wind", "'sounding' needs profile 'sounding'");
    if (wind == "layers") {
        try {
            windFrom(p, nullptr);
        } catch (const std::invalid_argument& e) {
            check.fail("windHeights", e.what());
        }
    }
}

}  // namespace

void registerAtmosphereNode(Registry& registry)
{
    NodeDecl d;
    d.type = "Atmosphere";
    d.version = 4;
    d.category = "atmosphere";
    d.doc =
        "The environment of Sec. 5.1: by default the paper's, ground temperature and "
        "environmental lapse rate (Eq. 9, T_e = T_sl_max - C_e z), one dew-point threshold "
        "and the particle lapse rates of Eq. 8, and gravity (Eq. 6); the defaults put the "
        "cloud base of the default VapourEmitter at 1.4 km. Ours ("
        "docs/atmosphere.md): profile 'sounding' (a University of Wyoming or CSV sounding "
        "file; its parsed levels, not its path, enter the cache key) or 'standard' (ICAO) "
        "replaces Eq. 9 and the one T_dp: each particle then condenses at its own lifting "
        "condensation level and, saturated, cools at the moist adiabatic rate. A wind "
        "from the sounding or from layers moves the particles horizontally.";
    d.outputs = {port("atmosphere", "Atmosphere",
                      "the environment, for ThermalIntegrator and Condensation")};
    using L = AtmosphereLimits;  // the ranges a stored Atmosphere is checked against
    d.params = {
        floatParam("groundTemperature", 20.0, "degC",
                   "T_sl_max of Eq. 9: environment temperature at the ground (value ours; "
                   "profile 'linear' only)",
                   L::kMinTemperature, L::kMaxTemperature),
        floatParam("environmentLapseRate", 6.4, "degC/km",
                   "C_e of Eq. 9: environment cooling with height (paper: 6.4; profile "
                   "'linear' only)",
                   0, L::kMaxEnvironmentLapsePerKm),
        floatParam("dewPoint", 16.0, "degC",
                   "T_dp of Eq. 8: a particle colder than this condenses (value ours; profile "
                   "'linear' only)",
                   L::kMinTemperature, L::kMaxTemperature),
        floatParam("dryLapseRate", 10.0, "degC/km",
                   "C of Eq. 8 while T_v >= T_dp: dry particle cooling (paper: 10; the dry "
                   "adiabat is 9.76)",
                   0, L::kMaxParticleLapsePerKm),
        floatParam("moistLapseRate", 6.0, "degC/km",
                   "C of Eq. 8 once T_v < T_dp: moist particle cooling (paper: 6; with a "
                   "profile only when moistAdiabat is false)",
                   0, L::kMaxParticleLapsePerKm),
        floatParam("gravity", 9.81, "m/s^2", "g of Eq. 6", 0, L::kMaxGravity),
        stringParam("profile", "linear",
                    "ours: 'linear' (the paper's Eq. 9), 'sounding' (soundingFile) or "
                    "'standard' (ICAO: 6.5 degC/km to the tropopause, isothermal above)",
                    {"linear", "standard", "sounding"}),
        inputFileParam("soundingFile", "",
                       "profile 'sounding': a University of Wyoming text list or a CSV with "
                       "height_m,temperature_C,dewpoint_C (docs/atmosphere.md); a relative "
                       "path is found beside the graph file"),
        floatParam("surfaceTemperature", 25.0, "degC",
                   "profile 'standard': temperature at sea level (ICAO: 15; value ours)",
                   L::kMinTemperature, L::kMaxTemperature),
        floatParam("surfaceDewPoint", 17.0, "degC",
                   "profile 'standard': dew point at sea level; its depression is kept at "
                   "every height (value ours)",
                   L::kMinTemperature, L::kMaxTemperature),
        floatParam("tropopauseHeight", 11000.0, "m",
                   "profile 'standard': where the temperature stops falling (ICAO: 11000)", 1000.0,
                   19000.0),
        boolParam("moistAdiabat", true,
                  "with a profile: saturated particles cool at the moist adiabatic rate of "
                  "their temperature and the profile's pressure (ours); false: moistLapseRate"),
        stringParam("wind", "off",
                    "ours: 'off' (the paper: no wind), 'sounding' (the sounding's wind) or "
                    "'layers' (windHeights, windSpeeds, windDirections)",
                    {"off", "layers", "sounding"}),
        floatListParam("windHeights", {}, "m",
                       "wind 'layers': heights above the ground, increasing; linear between, "
                       "held outside (none: calm)",
                       0.0, L::kMaxProfileDepth),
        floatListParam("windSpeeds", {}, "m/s", "wind 'layers': speed at each height", 0.0,
                       L::kMaxWindSpeed),
        floatListParam("windDirections", {}, "deg",
                       "wind 'layers': the direction the wind blows from at each height, "
                       "clockwise from north (270: from the west, toward +x)",
                       0.0, 360.0),
        stringParam("windFrame", "ground",
                    "ours: 'ground' (winds as the sounding or layers give them) or 'storm' "
                    "(minus the mean wind below steeringDepth: the emission map moves with the "
                    "storm or the cloud field, the ground slides beneath it, and only the shear "
                    "around the mean wind tilts the clouds)",
                    {"ground", "storm"}),
        floatParam("steeringDepth", algo::kStormSteeringDepthM, "m",
                   "ours: windFrame 'storm' moves with the mean wind from the ground to this "
                   "height: 6 km for an ordinary storm (the usual estimate of its motion); a "
                   "shallow cumulus field drifts with its cloud layer, about its cloud tops",
                   10.0, L::kMaxProfileDepth),
    };
    d.validate = validate;
    d.hashExtra = [](const ParamSet& p, Hasher& h) {
        // The sounding's levels, not its path (the engine leaves input files out of the key),
        // so a copied or moved file is still a cache hit. An unreadable file fails at cook time
        // with its reason; until then its path stands in for the content.
        if (p.getString("profile") != "sounding") return;
        try {
            const auto profile = soundingProfile(p);
            h.str("levels");
            for (const algo::ProfileLevel& l : profile->levels())
                for (double v : {l.heightM, l.temperatureC, l.dewpointC, l.pressureHPa,
                                 l.windEastMs, l.windNorthMs})
                    h.f64(v);
        } catch (const std::exception&) {
            h.str("unreadable").str(p.getString("soundingFile"));
        }
    };
    d.create = [] { return std::make_unique<AtmosphereNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
