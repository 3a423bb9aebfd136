#pragma once
/// Neighbour search on a uniform cell grid (the O(N) search of Takeshita's method): points are
/// counting-sorted into cubic cells of edge >= the search radius, so the neighbours of a point
/// lie in the 27 cells around it. The order of the cell lists is the order of the input
/// indices, so every result is the same whatever the thread count.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace cg::algo {

class SphGrid {
public:
    /// A grid of cells of edge `cellSize` (m) covering the box [lo, hi] (m); points outside
    /// are clamped into the border cells, so nothing is ever lost.
    SphGrid(const double lo[3], const double hi[3], double cellSize);

    /// Sorts `count` points (xyz triples, m) into the cells. O(count + cells).
    void build(const double* xyz, std::size_t count);

    /// Calls f(j) for every point j with |x_j - p| < radius (radius <= cellSize), including
    /// a point at p itself, in a fixed order (cell by cell, then by index).
    template <typename F>
    void forEachNeighbour(const double* xyz, const double p[3], double radius, F&& f) const
    {
        const double r2 = radius * radius;
        int c[3];
        cellOf(p, c);
        for (int dz = -1; dz <= 1; ++dz) {
            const int z = c[2] + dz;
            if (z < 0 || z >= mDims[2]) continue;
            for (int dy = -1; dy <= 1; ++dy) {
                const int y = c[1] + dy;
                if (y < 0 || y >= mDims[1]) continue;
                const std::size_t row =
                    (static_cast<std::size_t>(z) * static_cast<std::size_t>(mDims[1]) +
                     static_cast<std::size_t>(y)) *
                    static_cast<std::size_t>(mDims[0]);
                const int x0 = c[0] > 0 ? c[0] - 1 : 0;
                const int x1 = c[0] + 1 < mDims[0] ? c[0] + 1 : mDims[0] - 1;
                // Cells x0..x1 of one row are contiguous in the sorted order.
                const std::uint32_t begin = mCellStart[row + static_cast<std::size_t>(x0)];
                const std::uint32_t end = mCellStart[row + static_cast<std::size_t>(x1) + 1];
                for (std::uint32_t k = begin; k < end; ++k) {
                    const std::uint32_t j = mSorted[k];
                    const double* q = xyz + 3 * static_cast<std::size_t>(j);
                    const double ex = q[0] - p[0], ey = q[1] - p[1], ez = q[2] - p[2];
                    if (ex * ex + ey * ey + ez * ez < r2) f(j);
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
    std::vector<std::uint32_t> mCellOfPoint;
};

}  // namespace cg::algo
