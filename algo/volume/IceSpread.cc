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

/// Box blur of half-width r over the n values at `index` (a line through the layer), zero
/// beyond its ends.
void boxLine(float* layer, const std::vector<long>& index, long r, std::vector<double>& line)
{
    const long n = static_cast<long>(index.size());
    line.resize(index.size());
    for (long i = 0; i < n; ++i) line[static_cast<std::size_t>(i)] = layer[index[i]];
    const double w = 1.0 / static_cast<double>(2 * r + 1);
    double sum = 0.0;
    for (long i = 0; i < std::min(r, n); ++i) sum += line[static_cast<std::size_t>(i)];
    for (long i = 0; i < n; ++i) {
        if (i + r < n) sum += line[static_cast<std::size_t>(i + r)];
        if (i - r - 1 >= 0) sum -= line[static_cast<std::size_t>(i - r - 1)];
        layer[index[static_cast<std::size_t>(i)]] = static_cast<float>(sum * w);
    }
}

/// The half-width of three box passes whose variance is sigma^2 (in steps).
long boxHalfWidth(double sigma)
{
    return std::max(1L, std::lround(0.5 * (std::sqrt(4.0 * sigma * sigma + 1.0) - 1.0)));
}

/// Three box passes of a Gaussian of `sigma` voxels along the direction (dx, dy) of a layer
/// (nx x ny, x fastest). The layer is cut into parallel lines, each voxel on one: along the
/// major axis one voxel a step, the minor coordinate rounded from the slope, so a step is
/// sqrt(1 + slope^2) voxels long.
void blurAlong(float* layer, long nx, long ny, double dx, double dy, double sigma)
{
    const bool alongX = std::abs(dx) >= std::abs(dy);
    const long major = alongX ? nx : ny, minor = alongX ? ny : nx;
    const double slope = alongX ? dy / dx : dx / dy;
    const long r = boxHalfWidth(sigma / std::sqrt(1.0 + slope * slope));
    const long reach = std::lround(slope * static_cast<double>(major - 1));
    std::vector<long> index;
    std::vector<double> line;
    for (int pass = 0; pass < 3; ++pass)
        for (long start = std::min(0L, -reach); start < minor + std::max(0L, -reach); ++start) {
            index.clear();
            for (long m = 0; m < major; ++m) {
                const long o = start + std::lround(slope * static_cast<double>(m));
                if (o < 0 || o >= minor) continue;
                index.push_back(alongX ? o * nx + m : m * nx + o);
            }
            if (!index.empty()) boxLine(layer, index, r, line);
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
    // Along the outflow's direction and across it; isotropic without one.
    const double speed = std::hypot(s.directionEast, s.directionNorth);
    const double dx = speed > 0.0 ? s.directionEast / speed : 1.0;
    const double dy = speed > 0.0 ? s.directionNorth / speed : 0.0;
    const double along = s.spread / voxel;
    const double across = (speed > 0.0 ? s.across : s.spread) / voxel;
    // Three passes reach three half-widths, each at most the larger sigma's.
    const long pad = 3 * boxHalfWidth(std::max(along, across)) + 2;
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
        blurAlong(layer, nx, ny, dx, dy, along);
        if (across > 0.0) blurAlong(layer, nx, ny, -dy, dx, across);
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
