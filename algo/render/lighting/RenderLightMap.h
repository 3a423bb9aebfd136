#pragma once
/// A light-transmittance volume: the optical depth τ(x) = ∫_0^∞ σ_t(x + s l) ds from any point
/// x toward a distant light in direction l, precomputed once per frame on a lattice aligned
/// with l (a "deep shadow map": columns parallel to l, one per texel of the plane across it),
/// so a shading sample needs one trilinear lookup instead of a shadow ray.
///
/// The map is sparse along the light: τ is 0 on the light's side of a column's occupied
/// texels and constant past them, so a column stores only the texels between, and a sparse cloud
/// field can have texels as fine as its voxels (a coarse map smears τ across the gaps
/// between thin clouds and darkens their single scattering).

#include <algorithm>
#include <cstddef>
#include <functional>
#include <vector>

#include <openvdb/openvdb.h>

#include "algo/render/RenderSettings.h"
#include "algo/render/media/RenderOccupancy.h"

namespace cg::algo {

class RenderLightMap {
public:
    /// An empty map: τ = 0 everywhere.
    RenderLightMap() = default;

    /// Fills the map for `grid` (linear transform) and direction `towardLight` (world, any
    /// length). σ_t = extinction (1/m) × density. The texel is texelVoxels voxels, grown until
    /// the map stores at most maxTexels texels (at least 16) and has at most maxTexels / 4
    /// columns; each column is integrated with the midpoint rule in steps of at most
    /// stepVoxels voxels, only where `occupancy` says the grid can be non-zero. Columns are
    /// filled in parallel; the result does not depend on thread count. Stops early (leaving
    /// the map incomplete) once `cancelled` returns true.
    RenderLightMap(const openvdb::FloatGrid& grid, const RenderOccupancy& occupancy,
                   const RenderVec3& towardLight, double extinction, double texelVoxels,
                   double stepVoxels, std::size_t maxTexels = std::size_t(8) << 20,
                   const std::function<bool()>& cancelled = {});

    /// τ at world point p (dimensionless), trilinear between lattice nodes. Outside the map
    /// across the light it is the nearest column's value; beyond either end along the light it
    /// is that end's value, which is exact as no density lies outside the map.
    double opticalDepth(const RenderVec3& p) const;

    /// τ through the whole column at p: from the far end of the map to the light. The optical
    /// depth from p away from the light is columnDepth(p) − opticalDepth(p).
    double columnDepth(const RenderVec3& p) const;

    bool empty() const { return mTau.empty(); }
    std::size_t storedTexels() const { return mTau.size(); }
    const RenderVec3& towardLight() const { return mW; }  ///< unit, world
    double texel() const { return mH; }                   ///< m

private:
    double lookup(const RenderVec3& p, bool farEnd) const;
    struct Column;
    /// τ at height iw of a column.
    double tauIn(const Column& c, int iw) const
    {
        if (iw >= c.hi) return 0.0;  // at or above the light end of the cloud (or no cloud)
        return mTau[c.offset + static_cast<std::size_t>(std::max(iw, c.lo) - c.lo)];
    }

    /// The texels a column stores: iw in [lo, hi]; τ = 0 above hi and τ(lo) below lo.
    struct Column {
        std::size_t offset = 0;  ///< of τ(lo) in mTau
        int lo = 0;
        int hi = -1;  ///< hi < lo: the column crosses no cloud, τ = 0
    };

    RenderVec3 mOrigin{0.0, 0.0, 0.0};  ///< world position of node (0, 0, 0)
    RenderVec3 mU{1.0, 0.0, 0.0}, mV{0.0, 1.0, 0.0}, mW{0.0, 0.0, 1.0};  ///< mW toward light
    double mH = 1.0;                                                     ///< texel, m
    int mN[3] = {0, 0, 0};
    std::vector<Column> mColumns;  ///< index iu * nv + iv
    std::vector<float> mTau;       ///< the columns' stored texels, one after another
};

}  // namespace cg::algo
