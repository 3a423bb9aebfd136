#pragma once
/// Trilinear density lookups for ray marches, equal bit for bit to OpenVDB's
/// BoxSampler::sample through an accessor wherever that is positive, without its eight trips
/// through the tree. A sample in a brick where the occupancy says no sample can be positive
/// is 0 at once: the grid is not read (most samples of a voxelized cloud's blocks). The
/// eight corners of a lookup lie in at most eight 8^3 leaves, each a neighbour of the others
/// along the axes: kept in eight slots chosen by the parity of the leaf's coordinates, they
/// never evict one another. Marching samples move a fraction of a voxel at a time, so the
/// leaves are nearly always those of the last lookup. One per thread.

#include <cstdint>

#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>

#include "algo/render/media/RenderOccupancy.h"

namespace cg::algo {

class TrilinearDensity {
public:
    /// `occupancy` is the grid's.
    TrilinearDensity(const openvdb::FloatGrid& grid, const RenderOccupancy& occupancy)
        : mAcc(grid.getConstAccessor()), mOcc(occupancy)
    {
    }

    /// The density at index-space point `xyz`: BoxSampler::sample(accessor, xyz) where that is
    /// positive, and 0 or BoxSampler's value where it is not.
    float sample(const openvdb::Vec3d& xyz)
    {
        const openvdb::Coord ijk(openvdb::math::Floor(xyz.x()), openvdb::math::Floor(xyz.y()),
                                 openvdb::math::Floor(xyz.z()));
        const openvdb::Coord block = RenderOccupancy::blockOfVoxel(ijk);
        if (block != mBlock) {
            mBlock = block;
            mBricks = mOcc.brickMask(block);
        }
        if (!((mBricks >> RenderOccupancy::brickBit(ijk)) & 1u)) return 0.0f;
        return interpolate(xyz, ijk);
    }

private:
    using Leaf = openvdb::FloatTree::LeafNodeType;
    static constexpr int kLast = Leaf::DIM - 1;

    /// The trilinear value at xyz, in the cell whose lowest corner is ijk. Out of line: most
    /// samples stop at the brick test above, which should stay small enough to inline.
    [[gnu::noinline]] float interpolate(const openvdb::Vec3d& xyz, const openvdb::Coord& ijk)
    {
        const openvdb::Vec3d uvw = xyz - ijk.asVec3d();
        float data[2][2][2];
        if ((ijk.x() & kLast) != kLast && (ijk.y() & kLast) != kLast &&
            (ijk.z() & kLast) != kLast) {
            // All eight in one leaf (7 times in 8 per axis).
            const Slot& slot = slotFor(ijk);
            if (!slot.leaf) return slot.uniform;  // all eight corners equal
            const openvdb::Index at = Leaf::coordToOffset(ijk);
            for (int dx = 0; dx < 2; ++dx)
                for (int dy = 0; dy < 2; ++dy)
                    for (int dz = 0; dz < 2; ++dz)
                        data[dx][dy][dz] = slot.leaf->getValue(at + offset(dx, dy, dz));
        } else {
            for (int dx = 0; dx < 2; ++dx)
                for (int dy = 0; dy < 2; ++dy)
                    for (int dz = 0; dz < 2; ++dz) {
                        const openvdb::Coord corner = ijk.offsetBy(dx, dy, dz);
                        const Slot& slot = slotFor(corner);
                        data[dx][dy][dz] = slot.leaf
                                               ? slot.leaf->getValue(Leaf::coordToOffset(corner))
                                               : slot.uniform;
                    }
        }
        return openvdb::tools::BoxSampler::trilinearInterpolation(data, uvw);
    }

    struct Slot {
        openvdb::Coord origin{openvdb::Coord::max()};  ///< no leaf has this origin
        const Leaf* leaf = nullptr;
        float uniform = 0.0f;  ///< the value everywhere in the region when it has no leaf
    };

    static openvdb::Index offset(int dx, int dy, int dz)
    {
        return openvdb::Index((dx << (2 * Leaf::LOG2DIM)) + (dy << Leaf::LOG2DIM) + dz);
    }

    /// The slot of the leaf region holding voxel ijk, filled if it holds another region.
    const Slot& slotFor(const openvdb::Coord& ijk)
    {
        const int parity = ((ijk.x() >> Leaf::LOG2DIM) & 1) |
                           (((ijk.y() >> Leaf::LOG2DIM) & 1) << 1) |
                           (((ijk.z() >> Leaf::LOG2DIM) & 1) << 2);
        Slot& slot = mSlots[parity];
        const openvdb::Coord origin = ijk & ~kLast;
        if (slot.origin != origin) {
            slot.origin = origin;
            slot.leaf = mAcc.probeConstLeaf(ijk);
            slot.uniform = slot.leaf ? 0.0f : mAcc.getValue(ijk);
        }
        return slot;
    }

    openvdb::FloatGrid::ConstAccessor mAcc;
    const RenderOccupancy& mOcc;
    openvdb::Coord mBlock{openvdb::Coord::max()};  ///< of mBricks; no block has this one
    std::uint64_t mBricks = 0;
    Slot mSlots[8];
};

}  // namespace cg::algo
