#include "algo/render/media/RenderOccupancy.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "util/CheckedSize.h"

namespace cg::algo {

namespace {

/// Domains of more blocks keep no brick masks (8 bytes a block): 128 MB at most.
constexpr std::uint64_t kMostBrickBlocks = std::uint64_t(1) << 24;

/// The most blocks a domain may have: 128 MB of occupancy bytes.
constexpr std::uint64_t kMostBlocks = std::uint64_t(1) << 27;

/// Floor division by the block size for possibly negative coordinates. In 64 bits: a voxel
/// one past the int range (an active voxel at its edge, widened by the sampling margin) must
/// not wrap to the other end of it.
int blockOf(std::int64_t voxel)
{
    return static_cast<int>(voxel >= 0 ? voxel / 8 : -((-voxel + 7) / 8));
}

/// The blocks of the voxels next to `voxel` below and above it: a trilinear sample's reach.
int blockBelow(int voxel) { return blockOf(std::int64_t(voxel) - 1); }
int blockAbove(int voxel) { return blockOf(std::int64_t(voxel) + 1); }

/// Why a domain of n[0] x n[1] x n[2] blocks cannot be rendered, or empty. The extents, not
/// their product, are checked and named: the product of far-apart voxels' extents can wrap.
std::string blocksProblem(const std::int64_t (&n)[3])
{
    if (util::productWithin({n[0], n[1], n[2]}, kMostBlocks)) return "";
    return "fog volume spans too large a domain to render (" +
           util::extentsText({n[0], n[1], n[2]}) +
           " blocks of 8^3 voxels, more than 2^27; its active voxels lie too far apart)";
}

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

RenderOccupancy::RenderOccupancy(const openvdb::FloatTree& tree, bool majorants)
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
            lo[a] = std::min(lo[a], blockBelow(b.min()[a]));
            hi[a] = std::max(hi[a], blockAbove(b.max()[a]));
        }
    });
    if (!any) return;

    // Blocks lie within +-2^28 of the origin, so an extent fits an int; their product need
    // not fit 64 bits (two voxels 2^25 apart on every axis make 2^66 blocks).
    const std::int64_t n[3] = {std::int64_t(hi[0]) - lo[0] + 1, std::int64_t(hi[1]) - lo[1] + 1,
                               std::int64_t(hi[2]) - lo[2] + 1};
    if (const std::string problem = blocksProblem(n); !problem.empty())
        throw std::invalid_argument(problem);
    const auto total = static_cast<std::uint64_t>(n[0] * n[1] * n[2]);  // checked just above
    for (int a = 0; a < 3; ++a) {
        mMin[a] = lo[a];
        mN[a] = static_cast<int>(n[a]);
    }
    mOcc.assign(static_cast<std::size_t>(total), 0);
    forEachActiveBox(tree, [&](const openvdb::CoordBBox& b) {
        int b0[3], b1[3];
        for (int a = 0; a < 3; ++a) {
            b0[a] = blockBelow(b.min()[a]) - mMin[a];
            b1[a] = blockAbove(b.max()[a]) - mMin[a];
        }
        for (int i = b0[0]; i <= b1[0]; ++i)
            for (int j = b0[1]; j <= b1[1]; ++j)
                for (int k = b0[2]; k <= b1[2]; ++k) mOcc[blockIndex(i, j, k)] = 1;
    });
    if (majorants) recordMajorants(tree);
    if (total <= kMostBrickBlocks) {
        recordBricks(tree);
        trimToBricks();
    }
}

std::string RenderOccupancy::domainProblem(const openvdb::CoordBBox& activeBox)
{
    if (activeBox.empty()) return "";
    // Leaves and tiles are aligned to the block size, so the constructor's domain runs from
    // the block below the first active voxel's block to the one above the last's.
    std::int64_t n[3];
    for (int a = 0; a < 3; ++a)
        n[a] = std::int64_t(blockOf(activeBox.max()[a])) - blockOf(activeBox.min()[a]) + 3;
    return blocksProblem(n);
}

void RenderOccupancy::trimToBricks()
{
    // near[o]: the bricks of the block at offset o = (di, dj, dk) that touch this block.
    std::uint64_t near[27];
    for (int o = 0; o < 27; ++o) {
        const int d[3] = {o / 9 - 1, o / 3 % 3 - 1, o % 3 - 1};
        near[o] = 0;
        for (int b = 0; b < 64; ++b) {
            const int brick[3] = {b & 3, (b >> 2) & 3, (b >> 4) & 3};
            bool touches = true;
            for (int a = 0; a < 3; ++a)
                touches = touches && (d[a] == 0 || brick[a] == (d[a] > 0 ? 0 : 3));
            if (touches) near[o] |= std::uint64_t(1) << bitOfBrick(brick[0], brick[1], brick[2]);
        }
    }
    // A block is kept while some sample in it or in a brick next to it can be positive: the
    // brick of margin keeps a sample whose floor lies just across a block face from being
    // lost to the DDA's rounding of where the ray crosses it.
    std::vector<std::uint8_t> kept(mOcc.size(), 0);
    tbb::parallel_for(0, mN[0], [&](int i) {
        for (int j = 0; j < mN[1]; ++j)
            for (int k = 0; k < mN[2]; ++k) {
                const std::size_t block = blockIndex(i, j, k);
                if (mOcc[block] == 0) continue;
                bool keep = false;
                for (int o = 0; o < 27 && !keep; ++o) {
                    const int n[3] = {i + o / 9 - 1, j + o / 3 % 3 - 1, k + o % 3 - 1};
                    if (n[0] < 0 || n[1] < 0 || n[2] < 0 || n[0] >= mN[0] || n[1] >= mN[1] ||
                        n[2] >= mN[2])
                        continue;
                    keep = (mBricks[blockIndex(n[0], n[1], n[2])] & near[o]) != 0;
                }
                kept[block] = keep ? 1 : 0;
            }
    });
    mOcc.swap(kept);
}

void RenderOccupancy::spans(const RenderVec3& origin, const RenderVec3& dir, double tMin,
                            double tMax, std::vector<Span>& out) const
{
    bool open = false;
    double start = 0.0, last = 0.0;
    walk(origin, dir, tMin, tMax, [&](std::size_t block, double t0, double t1) {
        if (mOcc[block] != 0) {
            if (!open) {
                open = true;
                start = t0;
            }
        } else if (open) {
            out.push_back({start, t0});
            open = false;
        }
        last = t1;
        return true;
    });
    if (open && start < last) out.push_back({start, last});
}

void RenderOccupancy::recordBricks(const openvdb::FloatTree& tree)
{
    mBricks.assign(mOcc.size(), 0);
    // Brick b (voxels 2b, 2b + 1 per axis) holds samples that read voxels 2b .. 2b + 2, so a
    // positive voxel v sets brick v / 2 and, when v is even, brick v / 2 − 1 too (which lies
    // in the block below when v is the first voxel of its block).
    const auto mark = [this](const openvdb::Coord& v) {
        int first[3], count[3];
        for (int a = 0; a < 3; ++a) {
            first[a] = (v[a] >> 1) - ((v[a] & 1) == 0 ? 1 : 0);
            count[a] = (v[a] & 1) == 0 ? 2 : 1;
        }
        for (int i = 0; i < count[0]; ++i)
            for (int j = 0; j < count[1]; ++j)
                for (int k = 0; k < count[2]; ++k) {
                    const int brick[3] = {first[0] + i, first[1] + j, first[2] + k};
                    const int b[3] = {(brick[0] >> 2) - mMin[0], (brick[1] >> 2) - mMin[1],
                                      (brick[2] >> 2) - mMin[2]};
                    if (b[0] < 0 || b[1] < 0 || b[2] < 0 || b[0] >= mN[0] || b[1] >= mN[1] ||
                        b[2] >= mN[2])
                        continue;  // outside the blocks, as in the occupancy
                    mBricks[blockIndex(b[0], b[1], b[2])] |=
                        std::uint64_t(1) << bitOfBrick(brick[0], brick[1], brick[2]);
                }
    };
    for (auto leaf = tree.cbeginLeaf(); leaf; ++leaf) {
        if (leaf->isEmpty()) continue;  // outside the blocks, as in the occupancy
        for (auto v = leaf->cbeginValueAll(); v; ++v)
            if (*v > 0.0f) mark(v.getCoord());
    }
    auto it = tree.cbeginValueOn();
    it.setMaxDepth(openvdb::FloatTree::ValueOnCIter::LEAF_DEPTH - 1);  // tiles only
    for (; it; ++it) {
        if (!(*it > 0.0f)) continue;
        openvdb::CoordBBox box;
        it.getBoundingBox(box);
        // Every brick of the blocks it touches, and of those whose samples reach its first
        // voxels: more than needed at its edges, never less.
        for (int i = blockBelow(box.min().x()); i <= blockOf(box.max().x()); ++i)
            for (int j = blockBelow(box.min().y()); j <= blockOf(box.max().y()); ++j)
                for (int k = blockBelow(box.min().z()); k <= blockOf(box.max().z()); ++k)
                    mBricks[blockIndex(i - mMin[0], j - mMin[1], k - mMin[2])] = ~std::uint64_t(0);
    }
}

void RenderOccupancy::recordMajorants(const openvdb::FloatTree& tree)
{
    mMax.assign(mOcc.size(), 0.0f);
    const auto raise = [this](int bi, int bj, int bk, float v) {
        float& m = mMax[blockIndex(bi - mMin[0], bj - mMin[1], bk - mMin[2])];
        m = std::max(m, v);
    };
    // A voxel at index i is read by trilinear samples in (i - 1, i + 1): its own block and,
    // on a leaf's faces, the neighbouring block. Leaves are block-aligned (8^3, origin a
    // multiple of 8), so each leaf raises the 27 blocks around it by the largest value of
    // the voxels that touch each.
    for (auto leaf = tree.cbeginLeaf(); leaf; ++leaf) {
        if (leaf->isEmpty()) continue;  // outside the blocks, as in the occupancy
        float near[27] = {};
        for (auto v = leaf->cbeginValueAll(); v; ++v) {
            const float value = *v;
            if (!(value > 0.0f)) continue;
            const openvdb::Coord local = v.getCoord() - leaf->origin();
            int from[3], to[3];
            for (int a = 0; a < 3; ++a) {
                from[a] = local[a] == 0 ? 0 : 1;
                to[a] = local[a] == kBlock - 1 ? 2 : 1;
            }
            for (int i = from[0]; i <= to[0]; ++i)
                for (int j = from[1]; j <= to[1]; ++j)
                    for (int k = from[2]; k <= to[2]; ++k) {
                        float& m = near[(i * 3 + j) * 3 + k];
                        m = std::max(m, value);
                    }
        }
        const openvdb::Coord b(blockOf(leaf->origin().x()), blockOf(leaf->origin().y()),
                               blockOf(leaf->origin().z()));
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                for (int k = 0; k < 3; ++k)
                    if (near[(i * 3 + j) * 3 + k] > 0.0f)
                        raise(b.x() + i - 1, b.y() + j - 1, b.z() + k - 1,
                              near[(i * 3 + j) * 3 + k]);
    }
    auto it = tree.cbeginValueOn();
    it.setMaxDepth(openvdb::FloatTree::ValueOnCIter::LEAF_DEPTH - 1);  // tiles only
    for (; it; ++it) {
        const float value = *it;
        if (!(value > 0.0f)) continue;
        openvdb::CoordBBox box;
        it.getBoundingBox(box);
        for (int i = blockBelow(box.min().x()); i <= blockAbove(box.max().x()); ++i)
            for (int j = blockBelow(box.min().y()); j <= blockAbove(box.max().y()); ++j)
                for (int k = blockBelow(box.min().z()); k <= blockAbove(box.max().z()); ++k)
                    raise(i, j, k, value);
    }
}

}  // namespace cg::algo
