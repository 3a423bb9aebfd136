#pragma once
/// What the Voxelizer needs from the atmosphere and the condensation to give its clouds flat
/// bases and water (algo/volume/CloudBase.h): the condensation level by column, and the
/// adiabatic water of a parcel saturated at that level; the water's optics and metadata.

#include <memory>

#include "algo/atmosphere/CloudWater.h"
#include "algo/volume/CloudBase.h"

namespace cg {

struct Atmosphere;
class CondensationData;
class CookContext;

/// The base field of the particles that have condensed, in cells of cellSize metres; null
/// while none has (there is no cloud yet).
std::unique_ptr<algo::CloudBaseField> cloudBaseOf(const CondensationData& condensation,
                                                  double cellSize);

/// The adiabatic water of a parcel saturated at height baseZ (m above the ground): at the
/// dew point T_dp (the paper's Eq. 8 condenses a parcel there), or with a sounding the air's
/// temperature there, and the pressure of environmentProfileOf(atmosphere) at that height.
algo::AdiabaticWater adiabaticWaterAt(const Atmosphere& atmosphere, double baseZ);

/// The Voxelizer's flatBase and optics 'water' (with its ice) on `grid`, from the node's
/// parameters and inputs; writes what a renderer needs into the grid's metadata. Nothing
/// when neither is asked for.
void shapeBaseAndWater(openvdb::FloatGrid& grid, CookContext& ctx);

}  // namespace cg
