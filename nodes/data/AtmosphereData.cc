#include "nodes/data/AtmosphereData.h"

#include "core/Registry.h"
#include "nodes/data/ValueChecks.h"

namespace cg {

namespace {

constexpr const char* kType = "Atmosphere";
constexpr double kPerKm = 1e-3;  // as the node converts, so its largest value passes exactly

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
    return a;
}

}  // namespace

bool AtmosphereData::serialize(ByteWriter& out) const
{
    for (double v : {atmosphere.groundTemperature, atmosphere.environmentLapse, atmosphere.dewPoint,
                     atmosphere.dryLapse, atmosphere.moistLapse, atmosphere.gravity})
        out.f64(v);
    return true;
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
