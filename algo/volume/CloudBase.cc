#include "algo/volume/CloudBase.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <openvdb/tools/Prune.h>
#include <openvdb/tree/LeafManager.h>

#include "algo/volume/LeafStore.h"

namespace cg::algo {

namespace {

using LeafT = openvdb::FloatTree::LeafNodeType;

double tenthPercentile(std::vector<double>& v)
{
    const std::size_t i = v.size() / 10;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(i), v.end());
    return v[i];
}

/// 0 at or below 0, 1 from 1 on, 3 s^2 - 2 s^3 between.
double smoothstep(double s)
{
    if (s <= 0.0) return 0.0;
    if (s >= 1.0) return 1.0;
    return s * s * (3.0 - 2.0 * s);
}

}  // namespace

CloudBaseField::CloudBaseField(const float* x, const float* y, const float* height, std::size_t n,
                               double cellSize)
    : mCell(cellSize)
{
    if (!(cellSize > 0.0)) throw std::invalid_argument("cloud base: cell size must be > 0");
    // Each finite point's cell, found once; cells beyond 2^30 of the origin are refused
    // before they are converted to integers.
    struct Point {
        long cx, cy;
        double height;
    };
    std::vector<Point> points;
    std::vector<double> all;
    constexpr double kMaxCell = 1 << 30;
    for (std::size_t i = 0; i < n; ++i) {
        if (!std::isfinite(height[i])) continue;
        const double fx = std::floor(x[i] / cellSize), fy = std::floor(y[i] / cellSize);
        if (!(std::abs(fx) < kMaxCell && std::abs(fy) < kMaxCell))
            throw std::invalid_argument("cloud base: a condensed particle lies too far out");
        points.push_back({static_cast<long>(fx), static_cast<long>(fy), height[i]});
        all.push_back(height[i]);
    }
    if (points.empty()) throw std::invalid_argument("cloud base: no particle has condensed");
    mOverall = tenthPercentile(all);
    const auto [minX, maxX] = std::minmax_element(
        points.begin(), points.end(), [](const Point& a, const Point& b) { return a.cx < b.cx; });
    const auto [minY, maxY] = std::minmax_element(
        points.begin(), points.end(), [](const Point& a, const Point& b) { return a.cy < b.cy; });
    mX0 = minX->cx, mY0 = minY->cy, mNx = maxX->cx - mX0 + 1, mNy = maxY->cy - mY0 + 1;
    if (mNx * mNy > (1L << 24))  // each below 2^31: the product fits
        throw std::invalid_argument("cloud base: the condensed particles span too many cells");
    std::vector<std::vector<double>> heights(static_cast<std::size_t>(mNx * mNy));
    for (const Point& p : points)
        heights[static_cast<std::size_t>((p.cy - mY0) * mNx + (p.cx - mX0))].push_back(p.height);
    mCells.resize(heights.size());
    for (std::size_t c = 0; c < heights.size(); ++c)
        mCells[c] = heights[c].empty() ? mOverall : tenthPercentile(heights[c]);
}

double CloudBaseField::cell(long i, long j) const
{
    i -= mX0, j -= mY0;
    if (i < 0 || j < 0 || i >= mNx || j >= mNy) return mOverall;
    return mCells[static_cast<std::size_t>(j * mNx + i)];
}

double CloudBaseField::at(double x, double y) const
{
    // Bilinear between cell centres.
    const double u = x / mCell - 0.5, v = y / mCell - 0.5;
    const double fu = std::floor(u), fv = std::floor(v);
    const long i = std::lround(fu), j = std::lround(fv);
    const double wu = u - fu, wv = v - fv;
    return (1 - wv) * ((1 - wu) * cell(i, j) + wu * cell(i + 1, j)) +
           wv * ((1 - wu) * cell(i, j + 1) + wu * cell(i + 1, j + 1));
}

double CloudBaseField::lowest() const
{
    double low = mOverall;
    for (double c : mCells) low = std::min(low, c);
    return low;
}

double extinctionPerUnitValue(const DropletPopulation& droplets)
{
    return extinctionFromWater(1.0, droplets);
}

namespace {

/// The value a voxel of splatted value v holds h metres above its base: the extinction of its
/// water, liquid and frozen, over that of 1 g/m^3 of liquid (`perUnit`).
double waterValue(double v, double h, const CloudWaterSettings& s, double perUnit)
{
    const double condensate = s.adiabaticFraction * v * s.water->at(h);
    const double ice = s.ice ? iceFraction(s.water->temperature(h), *s.ice) : 0.0;
    if (ice == 0.0) return std::cbrt(condensate * condensate);  // (LWC / 1 g m^-3)^(2/3)
    const double liquid = extinctionFromWater((1.0 - ice) * condensate, s.droplets);
    const double frozen =
        extinctionFromIce(ice * s.ice->retention * condensate, s.ice->effectiveRadius);
    return (liquid + frozen) / perUnit;
}

}  // namespace

void shapeCloudWater(openvdb::FloatGrid& grid, const CloudBaseField& base,
                     const CloudWaterSettings& s, const std::function<void()>& checkCancelled)
{
    if (!(s.transition > 0.0) || !(s.adiabaticFraction > 0.0))
        throw std::invalid_argument("cloud water: transition and adiabatic fraction must be > 0");
    if (s.ice) checkGlaciation(*s.ice);
    const double perUnit = extinctionPerUnitValue(s.droplets);
    const double voxel = grid.voxelSize()[0];
    openvdb::tree::LeafManager<openvdb::FloatTree> leaves(grid.tree());
    leaves.foreach ([&](LeafT& leaf, std::size_t) {
        constexpr int kDim = static_cast<int>(LeafT::DIM);
        const openvdb::Coord corner = leaf.origin();
        // The base under each of the leaf's columns, found once per column.
        double columnBase[kDim][kDim];
        for (int i = 0; i < kDim; ++i)
            for (int j = 0; j < kDim; ++j)
                columnBase[i][j] = base.at((corner.x() + i) * voxel, (corner.y() + j) * voxel);
        float* values = leaf.buffer().data();
        for (auto on = leaf.getValueMask().beginOn(); on; ++on) {
            const openvdb::Index n = on.pos();
            const int i = static_cast<int>(n >> (2 * LeafT::LOG2DIM));
            const int j = static_cast<int>((n >> LeafT::LOG2DIM) & (kDim - 1));
            const int k = static_cast<int>(n & (kDim - 1));
            const double h = (corner.z() + k) * voxel - columnBase[i][j];
            double v = values[n] * smoothstep(h / s.transition);
            if (s.water) v = waterValue(v, h, s, perUnit);
            storeOrSwitchOff(leaf, values, n, static_cast<float>(v));
        }
    });
    openvdb::tools::pruneInactive(grid.tree());
    if (checkCancelled) checkCancelled();
}

}  // namespace cg::algo
