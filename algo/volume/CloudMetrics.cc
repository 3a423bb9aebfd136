#include "algo/volume/CloudMetrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "algo/volume/CloudRegions.h"
#include "algo/volume/OutlineDimension.h"

namespace cg::algo {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A 2D array of doubles over [x0, x0 + width) x [y0, y0 + height).
struct Plane {
    int x0 = 0, y0 = 0, width = 0, height = 0;
    std::vector<double> v;

    Plane(int x0_, int y0_, int w, int h)
        : x0(x0_),
          y0(y0_),
          width(w),
          height(h),
          v(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0.0)
    {
    }
    double& at(int x, int y)
    {
        return v[static_cast<std::size_t>(y - y0) * static_cast<std::size_t>(width) +
                 static_cast<std::size_t>(x - x0)];
    }
};

double percentile(std::vector<double> values, double q)
{
    if (values.empty()) return kNaN;
    const std::size_t i = std::min(values.size() - 1, static_cast<std::size_t>(q * values.size()));
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(i), values.end());
    return values[i];
}

/// The mask of the cells >= 1, with one unset cell of margin on every side.
Mask2D maskAtLeastOne(const Plane& p)
{
    Mask2D m;
    m.width = p.width + 2;
    m.height = p.height + 2;
    m.set.assign(static_cast<std::size_t>(m.width) * static_cast<std::size_t>(m.height), 0);
    for (int y = 0; y < p.height; ++y)
        for (int x = 0; x < p.width; ++x)
            m.set[static_cast<std::size_t>(y + 1) * static_cast<std::size_t>(m.width) +
                  static_cast<std::size_t>(x + 1)] =
                p.v[static_cast<std::size_t>(y) * static_cast<std::size_t>(p.width) +
                    static_cast<std::size_t>(x)] >= 1.0;
    return m;
}

/// The side outline's box-counting dimension, boxes from 2 voxels to a quarter of the width
/// the silhouette spans.
double sideDimension(const Plane& side)
{
    const Mask2D m = maskAtLeastOne(side);
    int lo = m.width, hi = -1;
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x)
            if (m.at(x, y)) lo = std::min(lo, x), hi = std::max(hi, x);
    if (hi < lo) return kNaN;
    const int maxBox = (hi - lo + 1) / 4;
    if (maxBox < 8) return kNaN;
    return outlineDimension(m, 2, maxBox);
}

/// 2 x the slope of log P against log A over the clouds of at least kMinCloudPixels.
double areaPerimeter(const Plane& top, std::size_t& clouds)
{
    const Regions r = labelRegions(maskAtLeastOne(top));
    const std::vector<double>& areas = r.area;
    const std::vector<double>& perimeters = r.perimeter;
    double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
    for (std::size_t i = 0; i < areas.size(); ++i) {
        if (areas[i] < static_cast<double>(kMinCloudPixels)) continue;
        const double x = std::log(areas[i]), y = std::log(perimeters[i]);
        sx += x, sy += y, sxx += x * x, sxy += x * y, ++n;
    }
    clouds = static_cast<std::size_t>(n);
    const double det = n * sxx - sx * sx;
    if (n < 5 || det <= 0) return kNaN;
    return 2.0 * (n * sxy - sx * sy) / det;
}

/// Where, along `tau` (per voxel, in marching order), the running sum first reaches
/// `target`, in voxels from the start of the first voxel; NaN if it never does.
double reach(const std::vector<double>& tau, double target)
{
    double sum = 0;
    for (std::size_t i = 0; i < tau.size(); ++i) {
        if (tau[i] > 0 && sum + tau[i] >= target)
            return static_cast<double>(i) + (target - sum) / tau[i];
        sum += tau[i];
    }
    return kNaN;
}

/// The optical depth through the grid's active box along y (side: x by z) and along z (top:
/// x by y), tau = value x perVoxel summed.
struct Projections {
    Plane side, top;
};
Projections project(const openvdb::FloatGrid& grid, const openvdb::CoordBBox& box, double perVoxel)
{
    const openvdb::Coord lo = box.min(), dim = box.dim();
    Projections p{Plane(lo.x(), lo.z(), dim.x(), dim.z()), Plane(lo.x(), lo.y(), dim.x(), dim.y())};
    for (auto it = grid.cbeginValueOn(); it; ++it) {
        openvdb::CoordBBox b;
        it.getBoundingBox(b);
        const double tau = static_cast<double>(*it) * perVoxel;
        for (int x = b.min().x(); x <= b.max().x(); ++x)
            for (int y = b.min().y(); y <= b.max().y(); ++y)
                for (int z = b.min().z(); z <= b.max().z(); ++z) {
                    p.side.at(x, z) += tau;
                    p.top.at(x, y) += tau;
                }
    }
    return p;
}

}  // namespace

CloudMetrics measureCloud(const openvdb::FloatGrid& grid, const CloudMetricsOptions& options)
{
    CloudMetrics out;
    out.voxelSize = grid.voxelSize()[0];
    const double perVoxel = options.extinction * out.voxelSize;
    const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
    if (box.empty()) {
        out.sideOutlineDimension = out.topEdgeMedian = out.topEdgeP90 = kNaN;
        out.baseP10 = out.baseMedian = out.baseP90 = out.top = out.baseSpread = kNaN;
        out.areaPerimeterDimension = kNaN;
        return out;
    }
    const openvdb::Coord lo = box.min(), dim = box.dim();
    auto [side, top] = project(grid, box, perVoxel);
    out.sideOutlineDimension = sideDimension(side);
    out.areaPerimeterDimension = areaPerimeter(top, out.clouds);

    // Columns seen from above: profiles of tau from the bottom of the box up.
    auto acc = grid.getConstAccessor();
    std::vector<double> column(static_cast<std::size_t>(dim.z()));
    std::vector<double> edges, bases, tops;
    for (int y = lo.y(); y <= box.max().y(); ++y)
        for (int x = lo.x(); x <= box.max().x(); ++x) {
            const double total = top.at(x, y);
            if (total < 1.0) continue;
            for (int z = 0; z < dim.z(); ++z)
                column[static_cast<std::size_t>(z)] =
                    static_cast<double>(acc.getValue(openvdb::Coord(x, y, lo.z() + z))) * perVoxel;
            // Heights in m: voxel k spans (k - 0.5, k + 0.5) voxel sizes.
            const double bottom = (lo.z() - 0.5) * out.voxelSize;
            bases.push_back(bottom + reach(column, 0.5) * out.voxelSize);
            std::reverse(column.begin(), column.end());
            const double ceiling = (box.max().z() + 0.5) * out.voxelSize;
            tops.push_back(ceiling - reach(column, 0.5) * out.voxelSize);
            if (total >= options.thickColumnTau)
                edges.push_back((reach(column, 2.0) - reach(column, 0.1)) * out.voxelSize);
        }
    out.cloudColumns = bases.size();
    out.thickColumns = edges.size();
    out.topEdgeMedian = percentile(edges, 0.5);
    out.topEdgeP90 = percentile(edges, 0.9);
    out.baseP10 = percentile(bases, 0.1);
    out.baseMedian = percentile(bases, 0.5);
    out.baseP90 = percentile(bases, 0.9);
    out.top = tops.empty() ? kNaN : *std::max_element(tops.begin(), tops.end());
    out.baseSpread = (out.baseP90 - out.baseP10) / (out.top - out.baseMedian);
    return out;
}

SideView sideOpticalDepth(const openvdb::FloatGrid& grid, double extinction)
{
    const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
    if (box.empty()) return {};
    Plane side = project(grid, box, extinction * grid.voxelSize()[0]).side;
    return {side.width, side.height, std::move(side.v)};
}

TopView topOpticalDepth(const openvdb::FloatGrid& grid, double extinction)
{
    const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
    if (box.empty()) return {};
    Plane top = project(grid, box, extinction * grid.voxelSize()[0]).top;
    return {top.x0, top.y0, top.width, top.height, std::move(top.v)};
}

}  // namespace cg::algo
