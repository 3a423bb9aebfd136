#pragma once
/// Empty-space skipping for the volume renderer: a dense bit per 8³-voxel block of index space
/// (the size of an OpenVDB leaf), set where a trilinear sample of the grid can be non-zero,
/// and a 3D DDA (Amanatides & Woo 1987) that turns a ray into the intervals it spends in
/// such blocks. Inactive voxels are taken to hold zero, as in every fog volume.

#include <cstdint>
#include <vector>

#include <openvdb/openvdb.h>

#include "algo/render/RenderSettings.h"

namespace cg::algo {

class RenderOccupancy {
public:
    static constexpr int kBlock = 8;  ///< voxels per block edge

    struct Span {
        double t0;
        double t1;
    };

    /// Marks every block within one voxel of an active leaf voxel or active tile.
    /// Throws std::invalid_argument when the occupied blocks' bounding box exceeds 2^27 blocks
    /// (about 6e10 voxels), which no single cloud needs.
    explicit RenderOccupancy(const openvdb::FloatTree& tree);

    bool empty() const { return mOcc.empty(); }

    /// Appends to `out`, in increasing t, the intervals [t0, t1] within [tMin, tMax] where the
    /// index-space ray origin + t * dir crosses occupied blocks; runs of adjacent occupied
    /// blocks come out as one interval. `dir` need not be normalised.
    void spans(const RenderVec3& origin, const RenderVec3& dir, double tMin, double tMax,
               std::vector<Span>& out) const;

private:
    bool occupied(int i, int j, int k) const
    {
        return mOcc[(static_cast<std::size_t>(i) * static_cast<std::size_t>(mN[1]) +
                     static_cast<std::size_t>(j)) * static_cast<std::size_t>(mN[2]) +
                    static_cast<std::size_t>(k)] != 0;
    }

    int mMin[3] = {0, 0, 0};  ///< first block, in block units
    int mN[3] = {0, 0, 0};    ///< blocks per axis
    std::vector<std::uint8_t> mOcc;
};

}  // namespace cg::algo
