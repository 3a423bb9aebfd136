#pragma once
/// Neighbour search on a uniform cell grid (the O(N) search of Takeshita's method): points are
/// counting-sorted into cubic cells of edge >= the search radius, so the neighbours of a point
/// lie in the 27 cells around it. The order of the cell lists is the order of the input
/// indices, so every result is the same whatever the thread count.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace cg::algo {

class SphGrid {
public:
    /// A grid of cells of edge `cellSize` (m) covering the box [lo, hi] (m); points outside
    /// are clamped into the border cells, so nothing is ever lost.
    SphGrid(const double lo[3], const double hi[3], double cellSize);

    /// Sorts `count` points (xyz triples, m) into the cells, keeping a copy of their positions
    /// in cell order for the searches. O(count + cells).
    void build(const double* xyz, std::size_t count);

    /// Calls f(j) for every point j of the last build with |x_j - p| < radius (radius <=
    /// cellSize), including a point at p itself, in a fixed order (cell by cell, then by
    /// index). Cells that lie wholly farther than `radius` from p are not read: a point sees
    /// about 20 of its 27 cells.
    template <typename F>
    void forEachNeighbour(const double p[3], double radius, F&& f) const
    {
        const double r2 = radius * radius;
        int c[3];
        cellOf(p, c);
        // Per axis, the squared distance from p to the neighbouring cells below and above: a
        // lower bound for every point in them (points clamped into a border cell lie farther
        // out than the cell), less a margin for the rounding of the cell boundaries.
        double below[3], above[3];
        for (int a = 0; a < 3; ++a) {
            const double lower = mLo[a] + c[a] * mCell;
            below[a] = squaredGap(p[a] - lower);
            above[a] = squaredGap(lower + mCell - p[a]);
        }
        for (int dz = -1; dz <= 1; ++dz) {
            const int z = c[2] + dz;
            if (z < 0 || z >= mDims[2]) continue;
            const double gz = dz < 0 ? below[2] : dz > 0 ? above[2] : 0.0;
            if (gz >= r2) continue;
            for (int dy = -1; dy <= 1; ++dy) {
                const int y = c[1] + dy;
                if (y < 0 || y >= mDims[1]) continue;
                const double gyz = gz + (dy < 0 ? below[1] : dy > 0 ? above[1] : 0.0);
                if (gyz >= r2) continue;
                const std::size_t row =
                    (static_cast<std::size_t>(z) * static_cast<std::size_t>(mDims[1]) +
                     static_cast<std::size_t>(y)) *
                    static_cast<std::size_t>(mDims[0]);
                const int x0 = c[0] > 0 && gyz + below[0] < r2 ? c[0] - 1 : c[0];
                const int x1 = c[0] + 1 < mDims[0] && gyz + above[0] < r2 ? c[0] + 1 : c[0];
                // Cells x0..x1 of one row are contiguous in the sorted order.
                const std::uint32_t begin = mCellStart[row + static_cast<std::size_t>(x0)];
                const std::uint32_t end = mCellStart[row + static_cast<std::size_t>(x1) + 1];
                // The distance tests first, without branches (about one candidate in six
                // is a neighbour: a branch on each would be mispredicted), then the calls.
                std::uint32_t hits[kBatch];
                for (std::uint32_t first = begin; first < end; first += kBatch) {
                    const std::uint32_t last = std::min(end, first + kBatch);
                    std::uint32_t found = 0;
                    for (std::uint32_t k = first; k < last; ++k) {
                        const double* q = &mSortedXyz[3 * static_cast<std::size_t>(k)];
                        const double ex = q[0] - p[0], ey = q[1] - p[1], ez = q[2] - p[2];
                        hits[found] = k;
                        found += ex * ex + ey * ey + ez * ez < r2 ? 1u : 0u;
                    }
                    for (std::uint32_t h = 0; h < found; ++h) f(mSorted[hits[h]]);
                }
            }
        }
    }

    double cellSize() const { return mCell; }
    std::size_t cellCount() const { return mCellStart.size() - 1; }
    /// The cell index of point p (clamped into the grid).
    std::size_t cellIndex(const double p[3]) const
    {
        int c[3];
        cellOf(p, c);
        return (static_cast<std::size_t>(c[2]) * static_cast<std::size_t>(mDims[1]) +
                static_cast<std::size_t>(c[1])) *
                   static_cast<std::size_t>(mDims[0]) +
               static_cast<std::size_t>(c[0]);
    }

private:
    static constexpr std::uint32_t kBatch = 64;  ///< candidates tested per batch

    /// d^2 for a distance d to a cell boundary, less a margin; 0 when p is at the boundary.
    double squaredGap(double d) const
    {
        const double gap = d - 1e-9 * mCell;
        return gap > 0.0 ? gap * gap : 0.0;
    }

    void cellOf(const double p[3], int c[3]) const
    {
        for (int a = 0; a < 3; ++a) {
            const double f = (p[a] - mLo[a]) * mInvCell;
            int i = f > 0.0 ? static_cast<int>(f) : 0;
            c[a] = i < mDims[a] ? i : mDims[a] - 1;
        }
    }

    double mLo[3];
    double mCell;
    double mInvCell;
    int mDims[3];
    std::vector<std::uint32_t> mCellStart;  ///< first sorted slot of each cell, plus the end
    std::vector<std::uint32_t> mSorted;     ///< point indices, cell by cell
    std::vector<double> mSortedXyz;         ///< their positions, in the same order
    std::vector<std::uint32_t> mCellOfPoint;
};

}  // namespace cg::algo
