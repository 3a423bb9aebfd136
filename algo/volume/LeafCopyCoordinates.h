#pragma once
/// A leaf's voxels in their copies' own coordinates (the voxel's centre minus its copy
/// origin, algo/volume/CopyOriginField.h): what detail noise is evaluated at so it rides
/// with the copies. The per-axis positions and their places among the field's cells are
/// found once per leaf coordinate, not once per voxel.

#include <optional>

#include <openvdb/openvdb.h>

#include "algo/volume/CopyOriginField.h"

namespace cg::algo {

template <typename LeafT>
class LeafCopyCoordinates {
public:
    static constexpr int kDim = static_cast<int>(LeafT::DIM);

    /// `field` null: world coordinates.
    LeafCopyCoordinates(const LeafT& leaf, double voxelSize, const CopyOriginField* field)
    {
        const openvdb::Coord corner = leaf.origin();
        if (field) {
            const openvdb::CoordBBox box = leaf.getNodeBoundingBox();
            double lo[3], hi[3];
            for (int a = 0; a < 3; ++a) {
                lo[a] = box.min()[a] * voxelSize;
                hi[a] = box.max()[a] * voxelSize;
            }
            mBlock = field->block(lo, hi);
        }
        for (int a = 0; a < 3; ++a)
            for (int l = 0; l < kDim; ++l) {
                mMetres[a][l] = (corner[a] + l) * voxelSize;
                if (mBlock) mPlaces[a][l] = mBlock->place(a, mMetres[a][l]);
            }
    }

    /// Voxel n of the leaf (its linear offset) in its copy's coordinates. Every voxel a
    /// splat reached has an origin; a grid changed since (filtered, combined) may have
    /// others, which keep world coordinates.
    void at(openvdb::Index n, double x[3]) const
    {
        const int i = static_cast<int>(n >> (2 * LeafT::LOG2DIM));
        const int j = static_cast<int>((n >> LeafT::LOG2DIM) & (kDim - 1));
        const int k = static_cast<int>(n & (kDim - 1));
        x[0] = mMetres[0][i];
        x[1] = mMetres[1][j];
        x[2] = mMetres[2][k];
        if (!mBlock) return;
        double origin[3];
        const CopyOriginField::Block::AxisPlace places[3] = {mPlaces[0][i], mPlaces[1][j],
                                                             mPlaces[2][k]};
        if (!mBlock->origin(places, origin)) return;
        for (int a = 0; a < 3; ++a) x[a] -= origin[a];
    }

private:
    std::optional<CopyOriginField::Block> mBlock;
    double mMetres[3][kDim];
    CopyOriginField::Block::AxisPlace mPlaces[3][kDim];
};

}  // namespace cg::algo
