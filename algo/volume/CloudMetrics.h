#pragma once
/// How a fog volume's clouds compare with real cumulus, by the measures cloud physics uses:
/// the fractal dimension of the outline seen from the side and of the clouds' perimeters seen
/// from above (Lovejoy 1982: about 1.35), how crisp the tops are (the depth over which the
/// optical depth from above grows from 0.1 to 2; a real turret's surface is a few mean free
/// paths of 10-30 m), and how flat the bases are. Everything is measured on optical depth,
/// tau = sum of value * extinction * voxel size along the line of sight, so the numbers do not
/// depend on how the grid scales its values. "Cloud" is where the projected tau is >= 1.

#include <cstddef>
#include <vector>

#include <openvdb/openvdb.h>

namespace cg::algo {

struct CloudMetricsOptions {
    double extinction = 0.02;  ///< 1/m per unit of the grid's value
    /// Columns whose whole tau is at least this count for the top edge.
    double thickColumnTau = 5.0;
};

/// NaN where a measure had too little cloud to be taken.
struct CloudMetrics {
    double voxelSize = 0;  ///< m
    /// Box-counting dimension of the outline of the side silhouette (projection along y),
    /// boxes from 2 voxels to a quarter of the silhouette's width.
    double sideOutlineDimension = 0;
    /// Median and 90th percentile over thick columns of the depth, in m, over which tau from
    /// above grows from 0.1 to 2.
    double topEdgeMedian = 0, topEdgeP90 = 0;
    std::size_t thickColumns = 0;
    /// Over columns with tau >= 1: the height (m) at which tau from below reaches 0.5.
    double baseP10 = 0, baseMedian = 0, baseP90 = 0;
    /// Highest height (m) at which tau from above reaches 0.5, over the same columns.
    double top = 0;
    /// (baseP90 - baseP10) / (top - baseMedian).
    double baseSpread = 0;
    std::size_t cloudColumns = 0;
    /// Seen from above: the clouds (4-connected regions of columns with tau >= 1) of at least
    /// `kMinCloudPixels` columns, and 2 x the least-squares slope of log perimeter against log
    /// area over them (the area-perimeter dimension; NaN below 5 clouds).
    std::size_t clouds = 0;
    double areaPerimeterDimension = 0;
};

inline constexpr std::size_t kMinCloudPixels = 4;

CloudMetrics measureCloud(const openvdb::FloatGrid& grid, const CloudMetricsOptions& options);

/// The optical depth through the grid along y (the side view measureCloud's outline is
/// taken on), over the active voxels' bounding box: width = x extent, height = z extent,
/// row 0 the lowest z.
struct SideView {
    int width = 0, height = 0;
    std::vector<double> tau;
};
SideView sideOpticalDepth(const openvdb::FloatGrid& grid, double extinction);

/// The optical depth through the grid along z (seen from above), over the active voxels'
/// bounding box: cell (i, j) is the column at index (x0 + i, y0 + j), row j = 0 the lowest y.
struct TopView {
    int x0 = 0, y0 = 0, width = 0, height = 0;
    std::vector<double> tau;
};
TopView topOpticalDepth(const openvdb::FloatGrid& grid, double extinction);

}  // namespace cg::algo
