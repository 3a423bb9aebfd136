#include "nodes/volume/CloudWaterSetup.h"

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "algo/atmosphere/Parcel.h"
#include "algo/volume/IceSpread.h"
#include "core/Error.h"
#include "core/Node.h"
#include "nodes/data/AtmosphereData.h"
#include "nodes/data/VapourParticles.h"
#include "util/SystemMemory.h"

namespace cg {

namespace {

/// The droplets the parameters ask for: the air mass's k, and its typical number unless
/// dropletConcentration is set.
algo::DropletPopulation dropletsFrom(const ParamSet& p)
{
    algo::DropletPopulation d =
        p.getString("airMass") == "maritime" ? algo::kMaritimeDroplets : algo::kContinentalDroplets;
    if (p.getFloat("dropletConcentration") > 0.0)
        d.concentrationPerCm3 = p.getFloat("dropletConcentration");
    return d;
}

/// How the condensate freezes, from the parameters (microns to metres).
algo::Glaciation glaciationFrom(const ParamSet& p)
{
    algo::Glaciation g;
    g.startC = p.getFloat("glaciationStart");
    g.endC = p.getFloat("glaciationEnd");
    g.retention = p.getFloat("iceRetention");
    g.effectiveRadius = p.getFloat("iceEffectiveRadius") * 1e-6;
    return g;
}

/// What a renderer needs to read a water grid: one number turns its values into extinction
/// (1/m); the rest describes the droplets.
void writeWaterMetadata(openvdb::FloatGrid& grid, const algo::CloudWaterSettings& s)
{
    const algo::DropletPopulation& droplets = s.droplets;
    const double extinction = algo::extinctionPerUnitValue(droplets);
    const double radius = algo::effectiveRadius(1.0, droplets);
    grid.insertMeta("extinction", openvdb::FloatMetadata(static_cast<float>(extinction)));
    grid.insertMeta("albedo", openvdb::FloatMetadata(1.0f));
    grid.insertMeta("phase_asymmetry",
                    openvdb::FloatMetadata(static_cast<float>(algo::dropletAsymmetry(radius))));
    grid.insertMeta("droplet_concentration_cm3",
                    openvdb::DoubleMetadata(droplets.concentrationPerCm3));
    if (!s.ice) {
        grid.insertMeta("value_meaning",
                        openvdb::StringMetadata("extinction / 'extinction'; liquid water "
                                                "content = value^1.5 g/m^3"));
        return;
    }
    const algo::Glaciation& ice = *s.ice;
    grid.insertMeta("glaciation_start_c", openvdb::DoubleMetadata(ice.startC));
    grid.insertMeta("glaciation_end_c", openvdb::DoubleMetadata(ice.endC));
    grid.insertMeta("ice_retention", openvdb::DoubleMetadata(ice.retention));
    grid.insertMeta("ice_effective_radius_um", openvdb::DoubleMetadata(ice.effectiveRadius * 1e6));
    grid.insertMeta("value_meaning",
                    openvdb::StringMetadata("extinction / 'extinction'; where the cloud is "
                                            "warmer than glaciation_start_c, liquid water "
                                            "content = value^1.5 g/m^3"));
}

/// Where the outflow starts, m above the ground: `depth` under the equilibrium level of a
/// parcel lifted from the ground with the air's temperature and dew point there; NaN when
/// that parcel never rises freely.
double outflowBottom(const Atmosphere& a, double depth)
{
    const algo::EnvironmentProfile profile = environmentProfileOf(a);
    const algo::ParcelAscent parcel = algo::liftParcel(profile, profile.groundHeight());
    return parcel.elM - depth - profile.groundHeight();
}

/// The glaciated layers spread into a sheet (algo/volume/IceSpread.h), within the node's
/// memory limit.
void spreadTheIce(openvdb::FloatGrid& grid, const algo::CloudBaseField& base,
                  const algo::AdiabaticWater& water, const algo::Glaciation& ice,
                  const Atmosphere& atmosphere, CookContext& ctx)
{
    algo::IceSpreadSettings spread;
    spread.spread = ctx.params().getFloat("iceSpread");
    const double bottom = outflowBottom(atmosphere, ctx.params().getFloat("anvilDepth"));
    if (std::isnan(bottom)) return;  // no parcel rises freely: no anvil
    spread.outflowBottom = bottom;
    // The crystals drift with the wind where the outflow is full.
    const algo::Wind wind = atmosphere.wind.at(bottom + 1000.0);
    spread.across = ctx.params().getFloat("iceSpreadAcross");
    spread.directionEast = wind.east;
    spread.directionNorth = wind.north;
    spread.maxBytes = util::nodeAllocationLimitBytes();
    try {
        algo::spreadIce(grid, base, water, ice, spread, [&] { ctx.checkCancelled(); });
    } catch (const algo::IceSpreadTooLarge& e) {
        throw InputError(ctx.nodeId() + "/params/iceSpread", e.what());
    }
}

}  // namespace

std::unique_ptr<algo::CloudBaseField> cloudBaseOf(const CondensationData& condensation,
                                                  double cellSize)
{
    if (condensation.condensedCount() == 0) return nullptr;
    const VapourParticlesData& p = *condensation.particles;
    return std::make_unique<algo::CloudBaseField>(p.xs().data(), p.ys().data(),
                                                  condensation.condensedHeight.data(),
                                                  condensation.condensedHeight.size(), cellSize);
}

algo::AdiabaticWater adiabaticWaterAt(const Atmosphere& a, double baseZ)
{
    const algo::EnvironmentProfile profile = environmentProfileOf(a);
    const double pressure = profile.pressure(profile.groundHeight() + baseZ);
    // The paper's parcels condense at T_dp; a sounding's at the air's temperature there.
    return algo::AdiabaticWater(a.profile ? a.environmentTemperature(baseZ) : a.dewPoint, pressure);
}

/// Flat bases and, with optics 'water', the cloud's water (algo/volume/CloudBase.h); writes
/// what a renderer needs into the grid's metadata.
void shapeBaseAndWater(openvdb::FloatGrid& grid, CookContext& ctx)
{
    const ParamSet& p = ctx.params();
    const bool water = p.getString("optics") == "water";
    if (!water && !p.getBool("flatBase")) return;
    const auto condensation = ctx.input<CondensationData>("condensation");
    if (!condensation)
        throw InputError(ctx.nodeId() + "/inputs/condensation",
                         "flatBase and optics 'water' need the condensation input (the "
                         "condensation levels)");
    std::shared_ptr<const AtmosphereData> atmosphere;
    if (water) {
        atmosphere = ctx.input<AtmosphereData>("atmosphere");
        if (!atmosphere)
            throw InputError(ctx.nodeId() + "/inputs/atmosphere",
                             "optics 'water' needs the atmosphere input (the temperature and "
                             "pressure at the cloud base)");
    }
    algo::CloudWaterSettings s;
    s.transition = p.getFloat("baseTransition");
    s.adiabaticFraction = p.getFloat("adiabaticFraction");
    s.droplets = dropletsFrom(p);
    const algo::Glaciation ice = glaciationFrom(p);
    if (water && p.getBool("ice")) s.ice = &ice;
    const auto base = cloudBaseOf(*condensation, p.getFloat("baseCellSize"));
    if (!base) {
        // Nothing has condensed yet: no cloud base, and no liquid water anywhere.
        if (water) {
            grid.clear();
            writeWaterMetadata(grid, s);
        }
        return;
    }
    std::optional<algo::AdiabaticWater> adiabatic;
    if (water) {
        adiabatic.emplace(adiabaticWaterAt(atmosphere->atmosphere, base->overall()));
        s.water = &*adiabatic;
    }
    algo::shapeCloudWater(grid, *base, s, [&] { ctx.checkCancelled(); });
    if (s.ice) spreadTheIce(grid, *base, *adiabatic, *s.ice, atmosphere->atmosphere, ctx);
    grid.insertMeta("cloud_base_m", openvdb::DoubleMetadata(base->overall()));
    if (water) writeWaterMetadata(grid, s);
}

}  // namespace cg
