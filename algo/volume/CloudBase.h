#pragma once
/// Flat cloud bases at the condensation level, and a fog volume's values turned into the
/// cloud's water (ours; the paper's volume is "alpha values").
///
/// Rising air saturates at its condensation level, so a cumulus has no cloud below it and a
/// sharp, flat base there. The base is a height field: cells of `cellSize` metres each hold
/// the 10th percentile of the condensation heights of the particles that condensed in them
/// (each condenses at its own level, which a moisture map, a dew-point perturbation or a
/// sounding varies), cells without any the 10th percentile of all; between cell centres it
/// is bilinear. Below the base the density is cut to nothing, above it the splat's value is
/// multiplied by a smoothstep that reaches 1 `transition` metres up: the primitive's wake and
/// the splats' round undersides are cut off, not merely thinned.
///
/// Water: the splatted value v in [0, 1] (1 inside the cloud, falling to 0 at its soft, eroded
/// edge) is read as the share of the adiabatic water the air holds, so
/// LWC = adiabaticFraction v LWC_ad(z - base), which entrainment lowers toward the edges as in
/// real cumulus. The value stored is (LWC / 1 g m^-3)^(2/3), so extinction = value x
/// extinctionFromWater(1 g/m^3): the grid's value scales linearly to extinction, which is what
/// renderers (ours, Blender, Houdini, Karma) multiply by one density scale.
///
/// Ice: with settings.ice, the share iceFraction(T) of the condensate freezes at the parcel's
/// temperature T there (algo/atmosphere/CloudIce.h); the liquid keeps its droplets' optics,
/// the ice its retention's share with the crystals' optics, and the value stored is their
/// summed extinction over extinctionFromWater(1 g/m^3), so where there is no ice it is the
/// liquid's (LWC / 1 g m^-3)^(2/3) as before.

#include <cstddef>
#include <functional>
#include <vector>

#include <openvdb/openvdb.h>

#include "algo/atmosphere/CloudIce.h"
#include "algo/atmosphere/CloudWater.h"

namespace cg::algo {

/// The condensation level by column.
class CloudBaseField {
public:
    /// From the condensed particles' horizontal positions and condensation heights (metres,
    /// n of each); heights that are not finite are skipped. Throws std::invalid_argument for
    /// cellSize <= 0 or no finite height.
    CloudBaseField(const float* x, const float* y, const float* height, std::size_t n,
                   double cellSize);
    /// The base height (m) over (x, y).
    double at(double x, double y) const;
    /// The 10th percentile of all the heights: cells without particles, and what a
    /// condensation level for a whole cloud reads.
    double overall() const { return mOverall; }
    /// The lowest base over any column (bilinear values lie between their cells').
    double lowest() const;

private:
    double mCell;
    double mOverall = 0.0;
    long mX0 = 0, mY0 = 0;  ///< cell index of mCells[0]
    long mNx = 0, mNy = 0;
    std::vector<double> mCells;
    double cell(long i, long j) const;
};

struct CloudWaterSettings {
    double transition = 20.0;  ///< m over which the cut at the base rises from 0 to 1
    /// Null: values kept as the splat's density (only the cut); else the water's optics.
    const AdiabaticWater* water = nullptr;
    double adiabaticFraction = 0.6;
    DropletPopulation droplets;
    /// Null: the condensate stays liquid at any temperature; else it freezes (with water).
    const Glaciation* ice = nullptr;
};

/// Cuts `grid` at `base` and, with settings.water, turns its values into the water's
/// (see above), in place; voxels left at 0 are switched off. Deterministic for any thread
/// count (each voxel on its own). `checkCancelled` (optional) is called at the end.
void shapeCloudWater(openvdb::FloatGrid& grid, const CloudBaseField& base,
                     const CloudWaterSettings& settings,
                     const std::function<void()>& checkCancelled = {});

/// The extinction (1/m) of a value of 1 in a grid shapeCloudWater made with `droplets`.
double extinctionPerUnitValue(const DropletPopulation& droplets);

}  // namespace cg::algo
