#include "algo/volume/NearbyDepth.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace cg::algo {

namespace {

int floorDiv(double x, double cell) { return static_cast<int>(std::floor(x / cell)); }

}  // namespace

NearbyDepth::NearbyDepth(const openvdb::FloatGrid& sdf, double cell, double reach) : mCell(cell)
{
    const openvdb::CoordBBox box = sdf.evalActiveVoxelBoundingBox();
    if (box.empty()) return;
    const double voxel = sdf.voxelSize()[0];
    openvdb::Coord hi;
    for (int a = 0; a < 3; ++a) {
        mLo[a] = floorDiv(box.min()[a] * voxel, cell);
        hi[a] = floorDiv(box.max()[a] * voxel, cell);
        mDim[a] = hi[a] - mLo[a] + 1;
    }
    const auto index = [&](int i, int j, int k) {
        return (static_cast<std::size_t>(i) * mDim[1] + j) * mDim[2] + k;
    };
    mDepth.assign(static_cast<std::size_t>(mDim[0]) * mDim[1] * mDim[2], 0.0f);
    for (auto v = sdf.cbeginValueOn(); v; ++v) {
        const openvdb::Coord ijk = v.getCoord();
        const std::size_t c =
            index(floorDiv(ijk[0] * voxel, cell) - mLo[0], floorDiv(ijk[1] * voxel, cell) - mLo[1],
                  floorDiv(ijk[2] * voxel, cell) - mLo[2]);
        mDepth[c] = std::max(mDepth[c], -*v);
    }
    // The largest over the cells within reach, one axis at a time (a box).
    const int k = static_cast<int>(std::ceil(reach / cell));
    std::vector<float> pass(mDepth.size());
    for (int axis = 0; axis < 3; ++axis) {
        for (int i = 0; i < mDim[0]; ++i)
            for (int j = 0; j < mDim[1]; ++j)
                for (int l = 0; l < mDim[2]; ++l) {
                    int at[3] = {i, j, l};
                    const int centre = at[axis];
                    float best = 0.0f;
                    for (int o = std::max(0, centre - k); o <= std::min(mDim[axis] - 1, centre + k);
                         ++o) {
                        at[axis] = o;
                        best = std::max(best, mDepth[index(at[0], at[1], at[2])]);
                    }
                    pass[index(i, j, l)] = best;
                }
        mDepth.swap(pass);
    }
}

float NearbyDepth::cellValue(int i, int j, int k) const
{
    i = std::clamp(i, 0, mDim[0] - 1);
    j = std::clamp(j, 0, mDim[1] - 1);
    k = std::clamp(k, 0, mDim[2] - 1);
    return mDepth[(static_cast<std::size_t>(i) * mDim[1] + j) * mDim[2] + k];
}

std::pair<double, double> NearbyDepth::range(const double lo[3], const double hi[3]) const
{
    if (mDepth.empty()) return {0.0, 0.0};
    int first[3], last[3];
    for (int a = 0; a < 3; ++a) {
        first[a] = static_cast<int>(std::floor(lo[a] / mCell - 0.5)) - mLo[a];
        last[a] = static_cast<int>(std::floor(hi[a] / mCell - 0.5)) + 1 - mLo[a];
    }
    float least = cellValue(first[0], first[1], first[2]), most = least;
    for (int i = first[0]; i <= last[0]; ++i)
        for (int j = first[1]; j <= last[1]; ++j)
            for (int k = first[2]; k <= last[2]; ++k) {
                const float v = cellValue(i, j, k);
                least = std::min(least, v);
                most = std::max(most, v);
            }
    return {least, most};
}

double NearbyDepth::at(const double x[3]) const
{
    if (mDepth.empty()) return 0.0;
    int base[3];
    double t[3];
    for (int a = 0; a < 3; ++a) {
        const double u = x[a] / mCell - 0.5 - mLo[a];  // in cell centres
        const double f = std::floor(u);
        base[a] = static_cast<int>(f);
        t[a] = u - f;
    }
    double sum = 0.0;
    for (int c = 0; c < 8; ++c) {
        const int dx = c >> 2, dy = (c >> 1) & 1, dz = c & 1;
        const double w =
            (dx ? t[0] : 1.0 - t[0]) * (dy ? t[1] : 1.0 - t[1]) * (dz ? t[2] : 1.0 - t[2]);
        sum += w * cellValue(base[0] + dx, base[1] + dy, base[2] + dz);
    }
    return sum;
}

}  // namespace cg::algo
