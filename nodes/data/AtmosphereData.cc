#include "nodes/data/AtmosphereData.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/Registry.h"
#include "formats/Sounding.h"
#include "nodes/data/ValueChecks.h"

namespace cg {

namespace {

constexpr const char* kType = "Atmosphere";
constexpr double kPerKm = 1e-3;  // as the node converts, so its largest value passes exactly

constexpr std::size_t kProfileFields = 6;  // height, T, T_d, p, wind east, wind north
constexpr std::size_t kWindFields = 3;     // height, east, north

/// A profile as the node made it: at most a sounding's levels, every value filled in and
/// finite, heights increasing over at most kMaxProfileDepth; the constructor checks the rest.
void readProfile(ByteReader& in, Atmosphere& a)
{
    using L = AtmosphereLimits;
    const std::vector<double> v = in.podVector<double>();
    if (v.empty()) return;
    if (v.size() % kProfileFields != 0 || v.size() / kProfileFields > formats::kMaxSoundingLevels)
        checks::refuse(kType, "a profile of " + std::to_string(v.size()) + " values");
    std::vector<algo::ProfileLevel> levels;
    for (std::size_t k = 0; k < v.size(); k += kProfileFields) {
        algo::ProfileLevel l;
        l.heightM = checks::finiteIn(v[k], -1e4, 1e5, kType, "profile height");
        l.temperatureC = checks::finiteIn(v[k + 1], -150.0, 100.0, kType, "profile temperature");
        l.dewpointC = checks::finiteIn(v[k + 2], -200.0, 100.0, kType, "profile dew point");
        l.pressureHPa = checks::finiteIn(v[k + 3], 1e-6, 1200.0, kType, "profile pressure");
        l.windEastMs =
            checks::finiteIn(v[k + 4], -L::kMaxWindSpeed, L::kMaxWindSpeed, kType, "profile wind");
        l.windNorthMs =
            checks::finiteIn(v[k + 5], -L::kMaxWindSpeed, L::kMaxWindSpeed, kType, "profile wind");
        levels.push_back(l);
    }
    if (levels.back().heightM - levels.front().heightM > L::kMaxProfileDepth)
        checks::refuse(kType, "a profile deeper than the limit");
    const double windTop = in.f64();
    try {
        a.profile = std::make_shared<algo::EnvironmentProfile>(std::move(levels), windTop);
    } catch (const std::invalid_argument& e) {
        checks::refuse(kType, e.what());
    }
    a.moistAdiabat = checks::intIn(in.u64(), 0, 1, kType, "moist adiabat flag") == 1;
}

void readWind(ByteReader& in, Atmosphere& a)
{
    using L = AtmosphereLimits;
    const std::vector<double> v = in.podVector<double>();
    if (v.size() % kWindFields != 0 || v.size() / kWindFields > formats::kMaxSoundingLevels)
        checks::refuse(kType, "a wind profile of " + std::to_string(v.size()) + " values");
    std::vector<algo::WindLevel> levels;
    for (std::size_t k = 0; k < v.size(); k += kWindFields)
        levels.push_back(
            {checks::finiteIn(v[k], 0.0, L::kMaxProfileDepth, kType, "wind height"),
             checks::finiteIn(v[k + 1], -L::kMaxWindSpeed, L::kMaxWindSpeed, kType, "wind"),
             checks::finiteIn(v[k + 2], -L::kMaxWindSpeed, L::kMaxWindSpeed, kType, "wind")});
    try {
        a.wind = algo::WindProfile(std::move(levels));
    } catch (const std::invalid_argument& e) {
        checks::refuse(kType, e.what());
    }
}

Atmosphere readAtmosphere(ByteReader& in)
{
    using L = AtmosphereLimits;
    // Consumers step particles with these: each must be finite and one the node could make.
    Atmosphere a;
    a.groundTemperature = checks::finiteIn(in.f64(), L::kMinTemperature, L::kMaxTemperature, kType,
                                           "ground temperature");
    a.environmentLapse = checks::finiteIn(in.f64(), 0.0, L::kMaxEnvironmentLapsePerKm * kPerKm,
                                          kType, "environment lapse rate");
    a.dewPoint =
        checks::finiteIn(in.f64(), L::kMinTemperature, L::kMaxTemperature, kType, "dew point");
    a.dryLapse = checks::finiteIn(in.f64(), 0.0, L::kMaxParticleLapsePerKm * kPerKm, kType,
                                  "dry lapse rate");
    a.moistLapse = checks::finiteIn(in.f64(), 0.0, L::kMaxParticleLapsePerKm * kPerKm, kType,
                                    "moist lapse rate");
    a.gravity = checks::finiteIn(in.f64(), 0.0, L::kMaxGravity, kType, "gravity");
    readProfile(in, a);
    readWind(in, a);
    return a;
}

}  // namespace

bool AtmosphereData::serialize(ByteWriter& out) const
{
    for (double v : {atmosphere.groundTemperature, atmosphere.environmentLapse, atmosphere.dewPoint,
                     atmosphere.dryLapse, atmosphere.moistLapse, atmosphere.gravity})
        out.f64(v);
    std::vector<double> profile;
    if (atmosphere.profile)
        for (const algo::ProfileLevel& l : atmosphere.profile->levels())
            profile.insert(profile.end(), {l.heightM, l.temperatureC, l.dewpointC, l.pressureHPa,
                                           l.windEastMs, l.windNorthMs});
    out.podVector(profile);
    if (atmosphere.profile) {
        out.f64(atmosphere.profile->windTopHeight());
        out.u64(atmosphere.moistAdiabat ? 1 : 0);
    }
    std::vector<double> wind;
    for (const algo::WindLevel& l : atmosphere.wind.levels())
        wind.insert(wind.end(), {l.heightM, l.east, l.north});
    out.podVector(wind);
    return true;
}

std::size_t AtmosphereData::byteSize() const
{
    const std::size_t levels = atmosphere.profile ? atmosphere.profile->levels().size() : 0;
    const std::size_t samples = column.temperature.size() + column.dewpoint.size() +
                                column.pressure.size() + column.windEast.size() +
                                column.windNorth.size();
    return sizeof(*this) + levels * sizeof(algo::ProfileLevel) +
           atmosphere.wind.levels().size() * sizeof(algo::WindLevel) + samples * sizeof(float);
}

algo::EnvironmentProfile environmentProfileOf(const Atmosphere& a)
{
    if (a.profile) return *a.profile;
    const double nan = std::nan("");
    return algo::EnvironmentProfile(
        {{0.0, a.groundTemperature, a.dewPoint, nan, 0.0, 0.0},
         {20000.0, a.environmentTemperature(20000.0), a.dewPoint, nan, 0.0, 0.0}});
}

void registerAtmosphereType(Registry& registry)
{
    registry.addDataType({"Atmosphere",
                          "the environment: ground temperature, lapse rates, dew point, g",
                          [](ByteReader& in) -> DataPtr {
                              return std::make_shared<AtmosphereData>(readAtmosphere(in));
                          }});
}

}  // namespace cg
