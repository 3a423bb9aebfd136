#pragma once
/// Which clouds of a field die and which are born between two moments: the field is seen from
/// above at several frames in between, each frame's clouds are linked to the next frame's
/// clouds they overlap once the field's drift with the wind is taken out, and a cloud of the
/// first frame is gone when no chain of links leads from it to a cloud of the last, a cloud of
/// the last new when no chain leads to it from the first. A cloud that splits or merges
/// counts as living on. Sample the frames closely enough that a cloud moves less than its
/// size, relative to the field, between two of them.

#include <cstddef>
#include <vector>

#include "algo/volume/CloudMetrics.h"
#include "algo/volume/CloudRegions.h"

namespace cg::algo {

/// One frame's clouds seen from above on the grid's index lattice: regions.label's cell (i, j)
/// is the column at index (x0 + i, y0 + j).
struct CoverFrame {
    int x0 = 0, y0 = 0;
    Regions regions;
};

/// The clouds of a view from above: columns of optical depth >= 1.
CoverFrame coverOf(const TopView& top);

/// The share of the rectangle [x0, x1) x [y0, y1) (metres) whose columns are cloud, a column
/// counting where its centre lies (voxel: the grid's voxel size). 0 for an empty rectangle.
double coverShare(const CoverFrame& f, double voxel, double x0, double y0, double x1, double y1);

/// A shift of whole columns, and the number of cloud columns that coincide under it.
struct Drift {
    int dx = 0, dy = 0;
    std::size_t overlap = 0;
};

/// The shift that moves the most cloud columns of `from` onto cloud columns of `to`: searched
/// over |dx|, |dy| <= maxShift counting every fourth column each way, then within 3 columns of
/// the best at every column (the first in scan order, dy then dx, on a tie).
Drift estimateDrift(const CoverFrame& from, const CoverFrame& to, int maxShift);

struct Turnover {
    /// Clouds of at least minCells columns in the first and the last frame.
    std::size_t firstClouds = 0, lastClouds = 0;
    std::size_t gone = 0;       ///< of firstClouds
    std::size_t born = 0;       ///< of lastClouds
    std::vector<Drift> drifts;  ///< between consecutive frames
};

/// Throws std::invalid_argument for fewer than two frames or maxShift < 0.
Turnover trackTurnover(const std::vector<CoverFrame>& frames, int maxShift, double minCells);

}  // namespace cg::algo
