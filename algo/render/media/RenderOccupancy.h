#pragma once
/// Empty-space skipping for the volume renderer: a dense bit per 8³-voxel block of index space
/// (the size of an OpenVDB leaf), set where a trilinear sample of the grid can be non-zero,
/// and a 3D DDA (Amanatides & Woo 1987) that turns a ray into the intervals it spends in
/// such blocks. Inactive voxels are taken to hold zero, as in every fog volume. On request it
/// also keeps each block's majorant, the largest value a trilinear sample inside the block can
/// take, which the path tracer's free-flight and shadow-ray tracking need.
///
/// Inside a block, 4³ bricks of 2³ voxels (a 64-bit mask per block) say more finely where a
/// sample can be positive: a march skips the samples of empty bricks without reading the
/// grid (TrilinearDensity), which in a voxelized cloud are most of the samples in its blocks.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <openvdb/openvdb.h>

#include "algo/render/RenderRays.h"
#include "algo/render/RenderSettings.h"

namespace cg::algo {

class RenderOccupancy {
public:
    static constexpr int kBlock = 8;  ///< voxels per block edge

    struct Span {
        double t0;
        double t1;
    };

    /// Marks every block within one voxel of an active leaf voxel or active tile; with
    /// `majorants`, also records each block's largest reachable value (negative values count
    /// as zero). Throws std::invalid_argument when the occupied blocks' bounding box exceeds
    /// 2^27 blocks (about 6e10 voxels), which no single cloud needs, however far apart its
    /// voxels lie (the block count is formed without overflow).
    explicit RenderOccupancy(const openvdb::FloatTree& tree, bool majorants = false);

    bool empty() const { return mOcc.empty(); }

    /// Why a tree whose active voxels span `activeBox` (as evalActiveVoxelBoundingBox gives
    /// it, or a VDB file records it) is too large a domain for the constructor, in the words
    /// it throws; empty when it is not. Lets a reader refuse such a volume before its voxels
    /// are read.
    static std::string domainProblem(const openvdb::CoordBBox& activeBox);

    /// The block (in block units) holding voxel ijk.
    static openvdb::Coord blockOfVoxel(const openvdb::Coord& ijk)
    {
        return openvdb::Coord(ijk.x() >> 3, ijk.y() >> 3, ijk.z() >> 3);
    }

    /// The brick mask of `block` (in block units), 0 outside the blocks: bit brickBit(ijk) is
    /// set where a trilinear sample whose floor is voxel ijk can be positive (some voxel it
    /// reads is > 0). All ones without brick masks.
    std::uint64_t brickMask(const openvdb::Coord& block) const
    {
        const int b[3] = {block.x() - mMin[0], block.y() - mMin[1], block.z() - mMin[2]};
        for (int a = 0; a < 3; ++a)
            if (b[a] < 0 || b[a] >= mN[a]) return 0;
        if (mBricks.empty()) return ~std::uint64_t(0);
        return mBricks[blockIndex(b[0], b[1], b[2])];
    }

    static int brickBit(const openvdb::Coord& ijk)
    {
        return bitOfBrick(ijk.x() >> 1, ijk.y() >> 1, ijk.z() >> 1);
    }

    /// The largest trilinear sample in block `block` (an index walk() passes); 0 without
    /// majorants.
    float majorant(std::size_t block) const { return mMax.empty() ? 0.0f : mMax[block]; }

    /// Calls fn(block, t0, t1) for every block the index-space ray origin + t * dir crosses
    /// within [tMin, tMax], in increasing t, until fn returns false. `dir` need not be
    /// normalised.
    template <class Fn>
    void walk(const RenderVec3& origin, const RenderVec3& dir, double tMin, double tMax,
              Fn&& fn) const;

    /// Appends to `out`, in increasing t, the intervals [t0, t1] within [tMin, tMax] where the
    /// index-space ray origin + t * dir crosses occupied blocks; runs of adjacent occupied
    /// blocks come out as one interval. `dir` need not be normalised.
    void spans(const RenderVec3& origin, const RenderVec3& dir, double tMin, double tMax,
               std::vector<Span>& out) const;

private:
    std::size_t blockIndex(int i, int j, int k) const
    {
        return (static_cast<std::size_t>(i) * static_cast<std::size_t>(mN[1]) +
                static_cast<std::size_t>(j)) *
                   static_cast<std::size_t>(mN[2]) +
               static_cast<std::size_t>(k);
    }

    /// The bit of brick (bx, by, bz) (in brick units) in its block's mask.
    static int bitOfBrick(int bx, int by, int bz)
    {
        return (bx & 3) | ((by & 3) << 2) | ((bz & 3) << 4);
    }

    void recordMajorants(const openvdb::FloatTree& tree);
    void recordBricks(const openvdb::FloatTree& tree);
    /// Leaves out of the spans the blocks where no sample, nor any in the bricks next to
    /// them, can be positive (most of the blocks that the one-voxel margin around each leaf
    /// adds); the walk and the majorants still see them.
    void trimToBricks();

    int mMin[3] = {0, 0, 0};  ///< first block, in block units
    int mN[3] = {0, 0, 0};    ///< blocks per axis
    std::vector<std::uint8_t> mOcc;
    std::vector<float> mMax;             ///< per block; empty unless majorants were asked for
    std::vector<std::uint64_t> mBricks;  ///< per block; empty over a domain too large for them
};

template <class Fn>
void RenderOccupancy::walk(const RenderVec3& origin, const RenderVec3& dir, double tMin,
                           double tMax, Fn&& fn) const
{
    if (mOcc.empty() || !(tMin < tMax)) return;
    constexpr double kInf = std::numeric_limits<double>::infinity();
    double lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
        lo[a] = double(mMin[a]) * kBlock;
        hi[a] = double(mMin[a] + mN[a]) * kBlock;
    }
    double t0 = tMin, t1 = tMax;
    if (!clipToBox(origin, dir, lo, hi, t0, t1) || !(t0 < t1)) return;

    int cell[3], step[3];
    double tNext[3], tDelta[3];
    for (int a = 0; a < 3; ++a) {
        const double p = origin[a] + dir[a] * t0;
        cell[a] = std::clamp(static_cast<int>(std::floor((p - lo[a]) / kBlock)), 0, mN[a] - 1);
        if (dir[a] > 0.0) {
            step[a] = 1;
            tNext[a] = (lo[a] + double(cell[a] + 1) * kBlock - origin[a]) / dir[a];
            tDelta[a] = kBlock / dir[a];
        } else if (dir[a] < 0.0) {
            step[a] = -1;
            tNext[a] = (lo[a] + double(cell[a]) * kBlock - origin[a]) / dir[a];
            tDelta[a] = -kBlock / dir[a];
        } else {
            step[a] = 0;
            tNext[a] = kInf;
            tDelta[a] = kInf;
        }
    }

    double t = t0;
    for (;;) {
        const int axis =
            tNext[0] < tNext[1] ? (tNext[0] < tNext[2] ? 0 : 2) : (tNext[1] < tNext[2] ? 1 : 2);
        const double tExit = std::min(tNext[axis], t1);
        if (!fn(blockIndex(cell[0], cell[1], cell[2]), t, tExit)) return;
        t = tExit;
        if (t >= t1) return;
        cell[axis] += step[axis];
        if (cell[axis] < 0 || cell[axis] >= mN[axis]) return;
        tNext[axis] += tDelta[axis];
    }
}

}  // namespace cg::algo
