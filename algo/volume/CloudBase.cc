#include "algo/volume/CloudBase.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <openvdb/tools/Prune.h>
#include <openvdb/tree/LeafManager.h>

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
    std::vector<double> all;
    long minX = std::numeric_limits<long>::max(), minY = minX,
         maxX = std::numeric_limits<long>::min(), maxY = maxX;
    std::vector<std::size_t> used;
    for (std::size_t i = 0; i < n; ++i) {
        if (!std::isfinite(height[i]) || !std::isfinite(x[i]) || !std::isfinite(y[i])) continue;
        const long cx = std::lround(std::floor(x[i] / cellSize));
        const long cy = std::lround(std::floor(y[i] / cellSize));
        minX = std::min(minX, cx), maxX = std::max(maxX, cx);
        minY = std::min(minY, cy), maxY = std::max(maxY, cy);
        all.push_back(height[i]);
        used.push_back(i);
    }
    if (all.empty()) throw std::invalid_argument("cloud base: no particle has condensed");
    mOverall = tenthPercentile(all);
    mX0 = minX, mY0 = minY, mNx = maxX - minX + 1, mNy = maxY - minY + 1;
    if (mNx * mNy > (1L << 24))
        throw std::invalid_argument("cloud base: the condensed particles span too many cells");
    std::vector<std::vector<double>> heights(static_cast<std::size_t>(mNx * mNy));
    for (const std::size_t i : used) {
        const long cx = std::lround(std::floor(x[i] / cellSize)) - mX0;
        const long cy = std::lround(std::floor(y[i] / cellSize)) - mY0;
        heights[static_cast<std::size_t>(cy * mNx + cx)].push_back(height[i]);
    }
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

double extinctionPerUnitValue(const DropletPopulation& droplets)
{
    return extinctionFromWater(1.0, droplets);
}

void shapeCloudWater(openvdb::FloatGrid& grid, const CloudBaseField& base,
                     const CloudWaterSettings& s, const std::function<void()>& checkCancelled)
{
    if (!(s.transition > 0.0) || !(s.adiabaticFraction > 0.0))
        throw std::invalid_argument("cloud water: transition and adiabatic fraction must be > 0");
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
            if (s.water) {
                const double lwc = s.adiabaticFraction * v * s.water->at(h);
                v = std::cbrt(lwc * lwc);  // (LWC / 1 g m^-3)^(2/3)
            }
            const auto value = static_cast<float>(v);
            if (value > 0.0f) {
                values[n] = value;
            } else {
                values[n] = 0.0f;
                leaf.setValueOff(n);
            }
        }
    });
    openvdb::tools::pruneInactive(grid.tree());
    if (checkCancelled) checkCancelled();
}

}  // namespace cg::algo
