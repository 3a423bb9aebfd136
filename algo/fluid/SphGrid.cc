#include "algo/fluid/SphGrid.h"

#include <cmath>
#include <stdexcept>

#include <tbb/parallel_for.h>

namespace cg::algo {

SphGrid::SphGrid(const double lo[3], const double hi[3], double cellSize)
    : mCell(cellSize), mInvCell(1.0 / cellSize)
{
    if (!(cellSize > 0.0)) throw std::invalid_argument("SphGrid: cell size must be positive");
    std::size_t cells = 1;
    for (int a = 0; a < 3; ++a) {
        mLo[a] = lo[a];
        const double extent = hi[a] - lo[a];
        if (!(extent >= 0.0)) throw std::invalid_argument("SphGrid: empty box");
        mDims[a] = std::max(1, static_cast<int>(std::ceil(extent * mInvCell)));
        cells *= static_cast<std::size_t>(mDims[a]);
    }
    if (cells > (std::size_t{1} << 28)) throw std::invalid_argument("SphGrid: too many cells");
    mCellStart.assign(cells + 1, 0);
}

void SphGrid::build(const double* xyz, std::size_t count)
{
    if (count >= (std::size_t{1} << 32) - 1)
        throw std::invalid_argument("SphGrid: too many points");
    mCellOfPoint.resize(count);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 4096),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i != r.end(); ++i)
                              mCellOfPoint[i] = static_cast<std::uint32_t>(cellIndex(xyz + 3 * i));
                      });
    // Counting sort, stable in the point index: the cell lists are in index order.
    std::fill(mCellStart.begin(), mCellStart.end(), 0u);
    for (std::size_t i = 0; i < count; ++i) ++mCellStart[mCellOfPoint[i] + 1];
    for (std::size_t c = 1; c < mCellStart.size(); ++c) mCellStart[c] += mCellStart[c - 1];
    mSorted.resize(count);
    std::vector<std::uint32_t> fill(mCellStart.begin(), mCellStart.end() - 1);
    for (std::size_t i = 0; i < count; ++i)
        mSorted[fill[mCellOfPoint[i]]++] = static_cast<std::uint32_t>(i);
    // The searches read positions in cell order: candidates side by side in memory.
    mSortedXyz.resize(3 * count);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 4096),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t k = r.begin(); k != r.end(); ++k)
                              for (int a = 0; a < 3; ++a)
                                  mSortedXyz[3 * k + a] =
                                      xyz[3 * static_cast<std::size_t>(mSorted[k]) + a];
                      });
}

}  // namespace cg::algo
