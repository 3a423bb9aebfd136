#pragma once
/// How deep a cloud is near each place: the largest depth (minus the signed distance) of a
/// distance field within about `reach` metres, so detail can be sized to the part of the
/// cloud it sits on (a thin turret takes smaller lumps than the tower's flank). Kept on
/// coarse cubic cells (the deepest active voxel of each, then the largest over the cells
/// within reach on every axis) and interpolated trilinearly between cell centres, so it
/// varies smoothly. Deterministic; no engine includes.

#include <utility>
#include <vector>

#include <openvdb/openvdb.h>

namespace cg::algo {

class NearbyDepth {
public:
    /// `sdf`: metres, negative inside, on a uniform transform. cell, reach > 0 metres.
    NearbyDepth(const openvdb::FloatGrid& sdf, double cell, double reach);

    /// The depth near x (world metres), >= 0; beyond the grid, its nearest cell's.
    double at(const double x[3]) const;
    /// The least and the largest value `at` can take in the box [lo, hi]: over the cells
    /// whose centres surround some point of it.
    std::pair<double, double> range(const double lo[3], const double hi[3]) const;

private:
    float cellValue(int i, int j, int k) const;

    double mCell;
    openvdb::Coord mLo;  ///< first coarse cell
    int mDim[3] = {0, 0, 0};
    std::vector<float> mDepth;
};

}  // namespace cg::algo
