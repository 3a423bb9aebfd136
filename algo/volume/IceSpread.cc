#include "algo/volume/IceSpread.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <openvdb/tools/Dense.h>
#include <tbb/parallel_for.h>

namespace cg::algo {

namespace {

using Dense = openvdb::tools::Dense<float, openvdb::tools::LayoutXYZ>;

/// Box blur of half-width r along a line of n values spaced `stride` apart, zero outside.
void boxLine(float* v, long n, long stride, long r, std::vector<double>& line)
{
    line.assign(static_cast<std::size_t>(n), 0.0);
    for (long i = 0; i < n; ++i) line[static_cast<std::size_t>(i)] = v[i * stride];
    const double w = 1.0 / static_cast<double>(2 * r + 1);
    double sum = 0.0;
    for (long i = 0; i < std::min(r, n); ++i) sum += line[static_cast<std::size_t>(i)];
    for (long i = 0; i < n; ++i) {
        if (i + r < n) sum += line[static_cast<std::size_t>(i + r)];
        if (i - r - 1 >= 0) sum -= line[static_cast<std::size_t>(i - r - 1)];
        v[i * stride] = static_cast<float>(sum * w);
    }
}

/// Three box passes along x and along y of one layer (nx x ny, x fastest): a Gaussian of
/// variance 3 ((2r + 1)^2 - 1) / 12 voxels^2.
void blurLayer(float* layer, long nx, long ny, long r)
{
    std::vector<double> line;
    for (int pass = 0; pass < 3; ++pass) {
        for (long j = 0; j < ny; ++j) boxLine(layer + j * nx, nx, 1, r, line);
        for (long i = 0; i < nx; ++i) boxLine(layer + i, ny, nx, r, line);
    }
}

/// The height above the base from which the parcel is colder than the first ice.
double firstIceHeight(const AdiabaticWater& water, const Glaciation& ice)
{
    for (double h = 0.0; h < 16000.0; h += 10.0)
        if (water.temperature(h) < ice.startC) return h;
    return 16000.0;
}

}  // namespace

void spreadIce(openvdb::FloatGrid& grid, const CloudBaseField& base, const AdiabaticWater& water,
               const Glaciation& ice, const IceSpreadSettings& s,
               const std::function<void()>& checkCancelled)
{
    if (!(s.spread > 0.0) || grid.activeVoxelCount() == 0) return;
    const double voxel = grid.voxelSize()[0];
    // Half-width of three box passes whose variance is spread^2.
    const double sigma = s.spread / voxel;
    const long r = std::max(1L, std::lround(0.5 * (std::sqrt(4.0 * sigma * sigma + 1.0) - 1.0)));
    const long pad = 3 * r;
    const openvdb::CoordBBox active = grid.evalActiveVoxelBoundingBox();
    const openvdb::Coord low(active.min().x() - static_cast<int>(pad),
                             active.min().y() - static_cast<int>(pad), active.min().z());
    const long nx = active.dim().x() + 2 * pad, ny = active.dim().y() + 2 * pad;
    // Each column's base, found once; only layers where some column could hold ice are spread.
    std::vector<double> columnBase(static_cast<std::size_t>(nx * ny));
    for (long j = 0; j < ny; ++j)
        for (long i = 0; i < nx; ++i)
            columnBase[static_cast<std::size_t>(j * nx + i)] =
                base.at((low.x() + i) * voxel, (low.y() + j) * voxel);
    const double lowestBase = *std::min_element(columnBase.begin(), columnBase.end());
    const int k0 =
        std::max(active.min().z(),
                 static_cast<int>(std::floor(
                     std::max(s.outflowBottom, lowestBase + firstIceHeight(water, ice)) / voxel)));
    if (k0 > active.max().z()) return;
    const openvdb::CoordBBox slab(
        openvdb::Coord(low.x(), low.y(), k0),
        openvdb::Coord(low.x() + static_cast<int>(nx) - 1, low.y() + static_cast<int>(ny) - 1,
                       active.max().z()));
    const long nz = slab.dim().z();
    const double bytes = 2.0 * sizeof(float) * static_cast<double>(nx) * static_cast<double>(ny) *
                         static_cast<double>(nz);
    if (s.maxBytes > 0 && bytes > static_cast<double>(s.maxBytes))
        throw IceSpreadTooLarge("ice spread: the glaciated layers (" + std::to_string(nx) + " x " +
                                std::to_string(ny) + " x " + std::to_string(nz) +
                                " voxels with the spread's margin) need more memory than allowed");
    Dense own(slab, 0.0f), spread(slab, 0.0f);
    openvdb::tools::copyToDense(grid, own);
    std::copy(own.data(), own.data() + own.valueCount(), spread.data());
    tbb::parallel_for(0L, nz, [&](long k) {
        float* layer = spread.data() + k * nx * ny;
        const float* mine = own.data() + k * nx * ny;
        blurLayer(layer, nx, ny, r);
        const double z = (slab.min().z() + k) * voxel;
        const double outflow = std::clamp((z - s.outflowBottom) / 1000.0, 0.0, 1.0);
        for (long n = 0; n < nx * ny; ++n) {
            const double w =
                outflow *
                iceFraction(water.temperature(z - columnBase[static_cast<std::size_t>(n)]), ice);
            layer[n] = static_cast<float>((1.0 - w) * mine[n] + w * layer[n]);
        }
    });
    if (checkCancelled) checkCancelled();
    openvdb::tools::copyFromDense(spread, grid, 2e-5f);
    if (checkCancelled) checkCancelled();
}

}  // namespace cg::algo
