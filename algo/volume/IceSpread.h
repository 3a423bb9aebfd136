#pragma once
/// The glaciated part of a cloud spread sideways into a sheet (ours; the paper's anvil is its
/// copies' puffs). A cumulonimbus's outflow spreads under the tropopause as a thin current of
/// air held flat by the stable stratification above it (Lilly 1988, "Cirrus outflow
/// dynamics"); its ice crystals drift apart and settle while the weak turbulence there mixes
/// out the rising turrets' lumps, so an anvil is a smooth sheet thinning at its edges, not a
/// row of cauliflower puffs. Each horizontal layer of the grid's values (extinction, the
/// Voxelizer's optics 'water') is blurred with a Gaussian of standard deviation `spread`
/// metres along the outflow's wind and `across` across it (three box passes each way, along
/// lines rasterized through the layer), which keeps the layer's summed extinction: crystals
/// drift far downwind and little sideways, so the puffs smear into streaks along the wind,
/// the fibres of a real anvil. Every voxel
/// takes w = iceFraction(T) x outflow(z) of the blurred value and the rest of its own. The
/// outflow share rises from 0 at `outflowBottom` to 1 a kilometre higher: the air spreads
/// where it has lost its buoyancy, near the equilibrium level, while the glaciated tower
/// below, still rising, keeps its column (the caller sets outflowBottom; the Voxelizer puts it
/// anvilDepth under the surface parcel's equilibrium level).

#include <cstdint>
#include <functional>
#include <stdexcept>

#include <openvdb/openvdb.h>

#include "algo/atmosphere/CloudIce.h"
#include "algo/atmosphere/CloudWater.h"
#include "algo/volume/CloudBase.h"

namespace cg::algo {

struct IceSpreadSettings {
    double spread = 3000.0;  ///< m, the Gaussian's standard deviation along; 0: nothing
    double across = 500.0;   ///< m, its standard deviation across the direction; 0: none
    /// The outflow's direction (any length; the wind there): zero for none, and then the
    /// spread is `spread` every way.
    double directionEast = 0.0, directionNorth = 0.0;
    double outflowBottom = 0.0;  ///< m, the grid's z where the spreading starts
    /// Refuse (IceSpreadTooLarge) when the dense layers would need more; 0: no limit.
    std::uint64_t maxBytes = 0;
};

/// The layers to spread would need more memory than IceSpreadSettings::maxBytes.
class IceSpreadTooLarge : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
};

/// Spreads the ice of `grid` (values as shapeCloudWater leaves them; T from `water` at the
/// height above `base`) in place. Voxels whose value falls below 2e-5 (an optical depth of
/// about 0.1 over 30 km) are switched off. Deterministic for any thread count.
void spreadIce(openvdb::FloatGrid& grid, const CloudBaseField& base, const AdiabaticWater& water,
               const Glaciation& ice, const IceSpreadSettings& settings,
               const std::function<void()>& checkCancelled = {});

}  // namespace cg::algo
