#include "nodes/data/AtmosphereData.h"

#include "core/Registry.h"

namespace cg {

bool AtmosphereData::serialize(ByteWriter& out) const
{
    for (double v : {atmosphere.groundTemperature, atmosphere.environmentLapse, atmosphere.dewPoint,
                     atmosphere.dryLapse, atmosphere.moistLapse, atmosphere.gravity})
        out.f64(v);
    return true;
}

void registerAtmosphereType(Registry& registry)
{
    registry.addDataType({"Atmosphere", "the environment: ground temperature, lapse rates, dew point, g",
                          [](ByteReader& in) -> DataPtr {
                              Atmosphere a;
                              a.groundTemperature = in.f64();
                              a.environmentLapse = in.f64();
                              a.dewPoint = in.f64();
                              a.dryLapse = in.f64();
                              a.moistLapse = in.f64();
                              a.gravity = in.f64();
                              return std::make_shared<AtmosphereData>(a);
                          }});
}

}  // namespace cg
