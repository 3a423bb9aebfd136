#pragma once
/// The environment of Sec. 5.1 (Eq. 8-9), in SI units: one source of truth for the thermal
/// integrator and for condensation.

#include <memory>

#include "algo/atmosphere/Column.h"
#include "algo/atmosphere/Profile.h"
#include "algo/atmosphere/Wind.h"
#include "core/Data.h"

namespace cg {

class Registry;

struct Atmosphere {
    double groundTemperature = 20.0;   ///< T_sl_max of Eq. 9, degrees C
    double environmentLapse = 6.4e-3;  ///< C_e of Eq. 9, degrees C per metre
    double dewPoint = 16.0;            ///< T_dp of Eq. 8, degrees C
    double dryLapse = 10.0e-3;         ///< C of Eq. 8 while T_v >= T_dp, degrees C per metre
    double moistLapse = 6.0e-3;        ///< C of Eq. 8 once T_v < T_dp, degrees C per metre
    double gravity = 9.81;             ///< g of Eq. 6, m/s^2

    /// Ours: the environment of a sounding or the standard atmosphere, in place of
    /// Eq. 9 and the one T_dp. Null: the paper's line.
    std::shared_ptr<const algo::EnvironmentProfile> profile;
    /// With a profile: saturated particles cool at the moist adiabatic rate, not moistLapse.
    bool moistAdiabat = true;
    /// Ours: horizontal wind by height above the ground; calm in the paper.
    algo::WindProfile wind;

    /// Eq. 9: T_e = T_sl_max - C_e * z, or the profile's temperature z above its ground.
    double environmentTemperature(double z) const
    {
        return profile ? profile->temperature(profile->groundHeight() + z)
                       : groundTemperature - environmentLapse * z;
    }
    /// Whether anything beyond the paper's Eq. 8-9 is asked for.
    bool beyondPaper() const { return profile || !wind.calm(); }
};

/// The ranges of the Atmosphere node's parameters (lapse rates per kilometre there, per metre
/// in Atmosphere): the node declares them from here, and a stored Atmosphere outside them is
/// refused.
struct AtmosphereLimits {
    static constexpr double kMinTemperature = -80.0, kMaxTemperature = 80.0;  ///< degrees C
    static constexpr double kMaxEnvironmentLapsePerKm = 20.0;
    static constexpr double kMaxParticleLapsePerKm = 50.0;  ///< dry and moist
    static constexpr double kMaxGravity = 100.0;            ///< m/s^2
    static constexpr double kMaxWindSpeed = 200.0;          ///< m/s
    static constexpr double kMaxProfileDepth = 100000.0;    ///< m, ground to top
};

class AtmosphereData final : public Data {
public:
    explicit AtmosphereData(const Atmosphere& a)
        : atmosphere(a), column(algo::sampleColumn(a.profile.get(), a.wind))
    {
    }
    const Atmosphere atmosphere;
    /// The profile and the wind as tables by height, sampled once here for every frame's
    /// steps (derived: not stored in the cache).
    const algo::EnvironmentColumn column;

    std::string typeName() const override { return "Atmosphere"; }
    std::size_t byteSize() const override;
    bool serialize(ByteWriter& out) const override;
};

/// The atmosphere as a profile: its own, or the paper's Eq. 9 line (T_e falling C_e per metre
/// to 20 km, the dew point T_dp everywhere, pressure hydrostatic from 1013.25 hPa at sea
/// level), so what reads temperatures and pressures by height works for both.
algo::EnvironmentProfile environmentProfileOf(const Atmosphere& a);

void registerAtmosphereType(Registry& registry);

}  // namespace cg
