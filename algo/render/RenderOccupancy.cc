#include "algo/render/RenderOccupancy.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace cg::algo {

namespace {

/// Floor division by the block size for possibly negative coordinates.
int blockOf(int voxel) { return voxel >= 0 ? voxel / 8 : -((-voxel + 7) / 8); }

/// Visits the index bounding box of every active tile and of every leaf with an active voxel.
template <class Fn>
void forEachActiveBox(const openvdb::FloatTree& tree, Fn&& fn)
{
    for (auto leaf = tree.cbeginLeaf(); leaf; ++leaf)
        if (!leaf->isEmpty()) fn(leaf->getNodeBoundingBox());
    auto it = tree.cbeginValueOn();
    it.setMaxDepth(openvdb::FloatTree::ValueOnCIter::LEAF_DEPTH - 1);  // tiles only
    for (; it; ++it) {
        openvdb::CoordBBox box;
        it.getBoundingBox(box);
        fn(box);
    }
}

}  // namespace

RenderOccupancy::RenderOccupancy(const openvdb::FloatTree& tree)
{
    // A trilinear sample at x reads voxels floor(x) and floor(x) + 1, so it can be non-zero
    // anywhere within one voxel of an active box.
    int lo[3] = {std::numeric_limits<int>::max(), std::numeric_limits<int>::max(),
                 std::numeric_limits<int>::max()};
    int hi[3] = {std::numeric_limits<int>::min(), std::numeric_limits<int>::min(),
                 std::numeric_limits<int>::min()};
    bool any = false;
    forEachActiveBox(tree, [&](const openvdb::CoordBBox& b) {
        any = true;
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], blockOf(b.min()[a] - 1));
            hi[a] = std::max(hi[a], blockOf(b.max()[a] + 1));
        }
    });
    if (!any) return;

    std::uint64_t total = 1;
    for (int a = 0; a < 3; ++a) {
        mMin[a] = lo[a];
        mN[a] = hi[a] - lo[a] + 1;
        total *= static_cast<std::uint64_t>(mN[a]);
    }
    if (total > (std::uint64_t(1) << 27))
        throw std::invalid_argument("fog volume spans too large a domain to render (" +
                                    std::to_string(total) + " blocks of 8^3 voxels)");
    mOcc.assign(static_cast<std::size_t>(total), 0);
    forEachActiveBox(tree, [&](const openvdb::CoordBBox& b) {
        int b0[3], b1[3];
        for (int a = 0; a < 3; ++a) {
            b0[a] = blockOf(b.min()[a] - 1) - mMin[a];
            b1[a] = blockOf(b.max()[a] + 1) - mMin[a];
        }
        for (int i = b0[0]; i <= b1[0]; ++i)
            for (int j = b0[1]; j <= b1[1]; ++j)
                for (int k = b0[2]; k <= b1[2]; ++k)
                    mOcc[(static_cast<std::size_t>(i) * static_cast<std::size_t>(mN[1]) +
                          static_cast<std::size_t>(j)) * static_cast<std::size_t>(mN[2]) +
                         static_cast<std::size_t>(k)] = 1;
    });
}

void RenderOccupancy::spans(const RenderVec3& origin, const RenderVec3& dir, double tMin,
                            double tMax, std::vector<Span>& out) const
{
    if (mOcc.empty() || !(tMin < tMax)) return;
    constexpr double kInf = std::numeric_limits<double>::infinity();
    double lo[3], hi[3];
    double t0 = tMin, t1 = tMax;
    for (int a = 0; a < 3; ++a) {
        lo[a] = double(mMin[a]) * kBlock;
        hi[a] = double(mMin[a] + mN[a]) * kBlock;
        if (dir[a] == 0.0) {
            if (origin[a] < lo[a] || origin[a] >= hi[a]) return;
            continue;
        }
        double ta = (lo[a] - origin[a]) / dir[a];
        double tb = (hi[a] - origin[a]) / dir[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    if (!(t0 < t1)) return;

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
    bool open = false;
    double start = 0.0;
    for (;;) {
        const int axis = tNext[0] < tNext[1] ? (tNext[0] < tNext[2] ? 0 : 2)
                                             : (tNext[1] < tNext[2] ? 1 : 2);
        const double tExit = std::min(tNext[axis], t1);
        if (occupied(cell[0], cell[1], cell[2])) {
            if (!open) {
                open = true;
                start = t;
            }
        } else if (open) {
            out.push_back({start, t});
            open = false;
        }
        t = tExit;
        if (t >= t1) break;
        cell[axis] += step[axis];
        if (cell[axis] < 0 || cell[axis] >= mN[axis]) break;
        tNext[axis] += tDelta[axis];
    }
    if (open && start < t) out.push_back({start, t});
}

}  // namespace cg::algo
