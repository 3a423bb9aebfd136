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

/// The lines a layer (nx x ny, x fastest) is cut into along a direction, every voxel on one:
/// along the major axis one voxel a step, the minor coordinate rounded from the slope, so a
/// step is sqrt(1 + slope^2) voxels long. The same for every layer, so found once.
struct Lines {
    std::vector<long> index;         ///< voxels, line after line
    std::vector<std::size_t> begin;  ///< where each line starts in `index`, and its end
    long halfWidth = 1;              ///< of three box passes of the blur's sigma, in steps
};

/// The half-width of three box passes whose variance is sigma^2 (in steps).
long boxHalfWidth(double sigma)
{
    return std::max(1L, std::lround(0.5 * (std::sqrt(4.0 * sigma * sigma + 1.0) - 1.0)));
}

/// The lines along (dx, dy) through a layer, for a Gaussian of `sigma` voxels.
Lines linesAlong(long nx, long ny, double dx, double dy, double sigma)
{
    const bool alongX = std::abs(dx) >= std::abs(dy);
    const long major = alongX ? nx : ny, minor = alongX ? ny : nx;
    const double slope = alongX ? dy / dx : dx / dy;
    const long reach = std::lround(slope * static_cast<double>(major - 1));
    Lines lines;
    lines.halfWidth = boxHalfWidth(sigma / std::sqrt(1.0 + slope * slope));
    lines.index.reserve(static_cast<std::size_t>(nx * ny));
    for (long start = std::min(0L, -reach); start < minor + std::max(0L, -reach); ++start) {
        const std::size_t first = lines.index.size();
        for (long m = 0; m < major; ++m) {
            const long o = start + std::lround(slope * static_cast<double>(m));
            if (o >= 0 && o < minor) lines.index.push_back(alongX ? o * nx + m : m * nx + o);
        }
        if (lines.index.size() > first) lines.begin.push_back(first);
    }
    lines.begin.push_back(lines.index.size());
    return lines;
}

/// Three box passes along every line of `lines` through `layer`, zero beyond a line's ends.
void blurAlong(float* layer, const Lines& lines, std::vector<double>& line)
{
    const long r = lines.halfWidth;
    const double w = 1.0 / static_cast<double>(2 * r + 1);
    for (int pass = 0; pass < 3; ++pass)
        for (std::size_t l = 0; l + 1 < lines.begin.size(); ++l) {
            const long* at = lines.index.data() + lines.begin[l];
            const long n = static_cast<long>(lines.begin[l + 1] - lines.begin[l]);
            line.resize(static_cast<std::size_t>(n));
            for (long i = 0; i < n; ++i) line[static_cast<std::size_t>(i)] = layer[at[i]];
            double sum = 0.0;
            for (long i = 0; i < std::min(r, n); ++i) sum += line[static_cast<std::size_t>(i)];
            for (long i = 0; i < n; ++i) {
                if (i + r < n) sum += line[static_cast<std::size_t>(i + r)];
                if (i - r - 1 >= 0) sum -= line[static_cast<std::size_t>(i - r - 1)];
                layer[at[i]] = static_cast<float>(sum * w);
            }
        }
}

/// The height above the base from which the parcel is colder than the first ice.
double firstIceHeight(const AdiabaticWater& water, const Glaciation& ice)
{
    for (double h = 0.0; h < 16000.0; h += 10.0)
        if (water.temperature(h) < ice.startC) return h;
    return 16000.0;
}

/// How each layer is blurred: along (dx, dy) and across it, sigmas in voxels, and the margin
/// three box passes reach.
struct Blur {
    double dx = 1.0, dy = 0.0, along = 0.0, across = 0.0;
    long pad = 0;
};

/// What spreads where: the grid's layers from k0 up, and which ice each voxel holds.
struct Layers {
    const CloudBaseField& base;
    const AdiabaticWater& water;
    const Glaciation& ice;
    const IceSpreadSettings& settings;
    int k0 = 0, k1 = 0;
};

/// Spreads the layers inside the columns of `box` (x, y; its margin included), which holds
/// every voxel the blur moves there: nothing outside it is read or written.
void spreadBox(openvdb::FloatGrid& grid, const openvdb::CoordBBox& box, const Blur& b,
               const Layers& l)
{
    const double voxel = grid.voxelSize()[0];
    const long nx = box.dim().x(), ny = box.dim().y(), nz = l.k1 - l.k0 + 1;
    // Two dense blocks, and the two directions' lines through one layer.
    const double bytes = (2.0 * sizeof(float) * static_cast<double>(nz) + 2.0 * sizeof(long)) *
                         static_cast<double>(nx) * static_cast<double>(ny);
    if (l.settings.maxBytes > 0 && bytes > static_cast<double>(l.settings.maxBytes))
        throw IceSpreadTooLarge("ice spread: the glaciated layers (" + std::to_string(nx) + " x " +
                                std::to_string(ny) + " x " + std::to_string(nz) +
                                " voxels with the spread's margin) need more memory than allowed");
    const openvdb::CoordBBox slab(openvdb::Coord(box.min().x(), box.min().y(), l.k0),
                                  openvdb::Coord(box.max().x(), box.max().y(), l.k1));
    std::vector<double> columnBase(static_cast<std::size_t>(nx * ny));  // once per column
    for (long j = 0; j < ny; ++j)
        for (long i = 0; i < nx; ++i)
            columnBase[static_cast<std::size_t>(j * nx + i)] =
                l.base.at((slab.min().x() + i) * voxel, (slab.min().y() + j) * voxel);
    Dense own(slab, 0.0f), spread(slab, 0.0f);
    openvdb::tools::copyToDense(grid, own);
    std::copy(own.data(), own.data() + own.valueCount(), spread.data());
    const Lines along = linesAlong(nx, ny, b.dx, b.dy, b.along);
    const Lines across = linesAlong(nx, ny, -b.dy, b.dx, b.across);
    tbb::parallel_for(0L, nz, [&](long k) {
        float* layer = spread.data() + k * nx * ny;
        const float* mine = own.data() + k * nx * ny;
        std::vector<double> line;
        blurAlong(layer, along, line);
        if (b.across > 0.0) blurAlong(layer, across, line);
        const double z = (slab.min().z() + k) * voxel;
        const double outflow = std::clamp((z - l.settings.outflowBottom) / 1000.0, 0.0, 1.0);
        for (long n = 0; n < nx * ny; ++n) {
            const double t = l.water.temperature(z - columnBase[static_cast<std::size_t>(n)]);
            const double w = outflow * iceFraction(t, l.ice);
            layer[n] = static_cast<float>((1.0 - w) * mine[n] + w * layer[n]);
        }
    });
    openvdb::tools::copyFromDense(spread, grid, 2e-5f);
}

/// Tiles of kTile x kTile columns: the unit in which separate clouds are found.
constexpr int kTile = 16;

/// The boxes (x, y in voxels) to spread separately: the tiles holding cloud in layers k0 and
/// up, grown by the blur's margin, in connected groups, each group's bounding box, boxes that
/// overlap merged. Clouds farther apart than the margin never meet in the blur, so spreading
/// each box alone is spreading the whole layer, without a dense layer over the empty sky
/// between scattered anvil remnants.
std::vector<openvdb::CoordBBox> cloudBoxes(const openvdb::FloatGrid& grid, int k0, long pad)
{
    const openvdb::CoordBBox active = grid.evalActiveVoxelBoundingBox();
    const int grow = static_cast<int>((pad + kTile - 1) / kTile) + 1;
    const int x0 = active.min().x() - grow * kTile, y0 = active.min().y() - grow * kTile;
    const int tx = active.dim().x() / kTile + 2 * grow + 2;
    const int ty = active.dim().y() / kTile + 2 * grow + 2;
    std::vector<std::uint8_t> cloud(static_cast<std::size_t>(tx) * ty, 0);
    for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) {
        if (leaf->origin().z() + 7 < k0 || leaf->isEmpty()) continue;
        for (int cx : {leaf->origin().x(), leaf->origin().x() + 7})
            for (int cy : {leaf->origin().y(), leaf->origin().y() + 7})
                cloud[static_cast<std::size_t>((cy - y0) / kTile) * tx + (cx - x0) / kTile] = 1;
    }
    // Grown by the margin (separably), then grouped 4-connected.
    std::vector<std::uint8_t> grown(cloud.size(), 0), rows(cloud.size(), 0);
    for (int j = 0; j < ty; ++j)
        for (int i = 0; i < tx; ++i)
            for (int d = -grow; d <= grow && !rows[static_cast<std::size_t>(j) * tx + i]; ++d)
                if (i + d >= 0 && i + d < tx && cloud[static_cast<std::size_t>(j) * tx + i + d])
                    rows[static_cast<std::size_t>(j) * tx + i] = 1;
    for (int j = 0; j < ty; ++j)
        for (int i = 0; i < tx; ++i)
            for (int d = -grow; d <= grow && !grown[static_cast<std::size_t>(j) * tx + i]; ++d)
                if (j + d >= 0 && j + d < ty && rows[static_cast<std::size_t>(j + d) * tx + i])
                    grown[static_cast<std::size_t>(j) * tx + i] = 1;
    std::vector<openvdb::CoordBBox> boxes;
    std::vector<std::uint8_t> seen(grown.size(), 0);
    std::vector<std::pair<int, int>> stack;
    for (int j = 0; j < ty; ++j)
        for (int i = 0; i < tx; ++i) {
            const std::size_t at = static_cast<std::size_t>(j) * tx + i;
            if (!grown[at] || seen[at]) continue;
            openvdb::CoordBBox box;
            seen[at] = 1;
            stack.emplace_back(i, j);
            while (!stack.empty()) {
                const auto [a, c] = stack.back();
                stack.pop_back();
                box.expand(openvdb::CoordBBox(
                    openvdb::Coord(x0 + a * kTile, y0 + c * kTile, 0),
                    openvdb::Coord(x0 + (a + 1) * kTile - 1, y0 + (c + 1) * kTile - 1, 0)));
                for (const auto& [na, nc] : {std::pair{a - 1, c}, std::pair{a + 1, c},
                                             std::pair{a, c - 1}, std::pair{a, c + 1}}) {
                    const std::size_t n = static_cast<std::size_t>(nc) * tx + na;
                    if (na < 0 || nc < 0 || na >= tx || nc >= ty || !grown[n] || seen[n]) continue;
                    seen[n] = 1;
                    stack.emplace_back(na, nc);
                }
            }
            boxes.push_back(box);
        }
    for (bool merged = true; merged;) {  // bounding boxes of L-shaped groups may overlap
        merged = false;
        for (std::size_t a = 0; a < boxes.size() && !merged; ++a)
            for (std::size_t c = a + 1; c < boxes.size() && !merged; ++c)
                if (boxes[a].hasOverlap(boxes[c])) {
                    boxes[a].expand(boxes[c]);
                    boxes.erase(boxes.begin() + static_cast<std::ptrdiff_t>(c));
                    merged = true;
                }
    }
    return boxes;
}

}  // namespace

void spreadIce(openvdb::FloatGrid& grid, const CloudBaseField& base, const AdiabaticWater& water,
               const Glaciation& ice, const IceSpreadSettings& s,
               const std::function<void()>& checkCancelled)
{
    if (!(s.spread > 0.0) || grid.activeVoxelCount() == 0) return;
    const double voxel = grid.voxelSize()[0];
    // Along the outflow's direction and across it; isotropic without one.
    Blur b;
    const double speed = std::hypot(s.directionEast, s.directionNorth);
    if (speed > 0.0) b.dx = s.directionEast / speed, b.dy = s.directionNorth / speed;
    b.along = s.spread / voxel;
    b.across = (speed > 0.0 ? s.across : s.spread) / voxel;
    // Three passes reach three half-widths, each at most the larger sigma's.
    b.pad = 3 * boxHalfWidth(std::max(b.along, b.across)) + 2;
    // Only layers where some column could hold ice are spread.
    const openvdb::CoordBBox active = grid.evalActiveVoxelBoundingBox();
    Layers l{base, water, ice, s};
    l.k0 = std::max(
        active.min().z(),
        static_cast<int>(std::floor(
            std::max(s.outflowBottom, base.lowest() + firstIceHeight(water, ice)) / voxel)));
    l.k1 = active.max().z();
    if (l.k0 > l.k1) return;
    const std::vector<openvdb::CoordBBox> boxes = cloudBoxes(grid, l.k0, b.pad);
    for (const openvdb::CoordBBox& box : boxes) {  // disjoint: any order gives the same grid
        spreadBox(grid, box, b, l);
        if (checkCancelled) checkCancelled();
    }
}

}  // namespace cg::algo
