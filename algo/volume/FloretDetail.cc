#include "algo/volume/FloretDetail.h"

#include <algorithm>
#include <cmath>

#include <openvdb/tools/FastSweeping.h>
#include <openvdb/tools/Morphology.h>
#include <openvdb/tools/Prune.h>
#include <openvdb/tree/LeafManager.h>

#include "algo/CounterRandom.h"
#include "algo/volume/LeafStore.h"
#include "algo/volume/NearbyDepth.h"

namespace cg::algo {

namespace {

using LeafT = openvdb::FloatTree::LeafNodeType;

/// The envelope's surface: where the splats' summed density crosses a half.
constexpr float kSurfaceValue = 0.5f;
/// Roots lie this deep inside the envelope, in largest radii (ours): the shallowest stand a
/// tenth of their radius out of it, the deepest are hidden beneath the sunken envelope.
constexpr double kShallowestRoot = 0.9;
constexpr double kDeepestRoot = 1.9;
/// Faces whose outward normal points further down than this sink less, and not at all past
/// kUnsunkNormalZ (ours): a cumulus base is flat and smooth.
constexpr double kSunkNormalZ = -0.3;
constexpr double kUnsunkNormalZ = -0.8;

double smoothstep(double edge0, double edge1, double x)
{
    const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

/// The vertical component of the distance field's unit gradient at ijk (the outward
/// normal), from central differences where both neighbours are active, one-sided where one
/// is; 0 where neither is.
double normalZ(const openvdb::FloatGrid::ConstAccessor& sdf, const openvdb::Coord& ijk, float s)
{
    double g[3];
    for (int a = 0; a < 3; ++a) {
        openvdb::Coord lo = ijk, hi = ijk;
        lo[a] -= 1;
        hi[a] += 1;
        float vlo = s, vhi = s;
        const bool hasLo = sdf.probeValue(lo, vlo), hasHi = sdf.probeValue(hi, vhi);
        const double span = (hasLo ? 1.0 : 0.0) + (hasHi ? 1.0 : 0.0);
        g[a] = span > 0.0 ? (static_cast<double>(vhi) - vlo) / span : 0.0;
    }
    const double length = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    return length > 0.0 ? g[2] / length : 0.0;
}

/// Sets every inactive voxel of every leaf to the background, 0.
void clearInactiveValues(openvdb::FloatGrid& grid)
{
    openvdb::tree::LeafManager<openvdb::FloatTree> leaves(grid.tree());
    leaves.foreach ([](LeafT& leaf, std::size_t) {
        for (auto off = leaf.getValueMask().beginOff(); off; ++off)
            leaf.setValueOnly(off.pos(), 0.0f);
    });
}

/// True when the iso-surface crosses the grid: otherwise fast sweeping leaves infinities.
bool hasSurface(const openvdb::FloatGrid& sdf)
{
    for (auto v = sdf.cbeginValueOn(); v; ++v)
        if (!std::isfinite(*v)) return false;
    return true;
}

/// The largest lumps a part of the cloud takes: deep enough parts r0, thinner ones a root's
/// deepest depth less, so every root that the part holds fits inside it.
class FloretSizes {
public:
    FloretSizes(const openvdb::FloatGrid& sdf, double radius)
        : mRadius(radius),
          mDepth(sdf, std::max(0.5 * radius, 2.0 * sdf.voxelSize()[0]), kDeepestRoot * radius)
    {
    }
    double at(const double world[3]) const
    {
        return std::min(mRadius, mDepth.at(world) / kDeepestRoot);
    }
    /// Whether some place in the box [lo, hi] may take roots of `radius`: its size there
    /// lies in [radius, 2 radius), or reaches r0 for the largest roots.
    bool mayHold(const double lo[3], const double hi[3], double radius) const
    {
        const auto [least, most] = mDepth.range(lo, hi);
        const double smallest = std::min(mRadius, least / kDeepestRoot);
        const double largest = std::min(mRadius, most / kDeepestRoot);
        return largest >= radius && (radius == mRadius || smallest < 2.0 * radius);
    }

private:
    double mRadius;
    NearbyDepth mDepth;
};

/// How far (metres) lumps can stand out of the envelope: a root's shallowest depth below
/// it less its radius, plus its descendants' reach.
double floretOverhang(const FloretSettings& s)
{
    return (1.0 - kShallowestRoot + (kFloretReach - 1.0)) * s.radius;
}

/// The roots that can reach the box [lo, hi] (world metres) and that `accept` keeps at
/// their world place, generation by generation, skipping the generations no place within
/// reach may take. Without a territory they lie on the world's lattice. With one, each copy
/// that owns a cell within reach places roots on the lattice of its own coordinates (its
/// seed mixed with its index) and keeps those inside its territory, so a root moves rigidly
/// with its copy; the roots come back in world coordinates.
std::vector<FloretRoot> rootsNear(const double lo[3], const double hi[3], const FloretSettings& s,
                                  const FloretSizes& sizes, const CopyTerritory* territory,
                                  const RootTest& accept)
{
    std::vector<FloretRoot> roots;
    for (int g = 0; g < s.levels; ++g) {
        const double radius = std::ldexp(s.radius, -g), reach = kFloretReach * radius;
        const double wideLo[3] = {lo[0] - reach, lo[1] - reach, lo[2] - reach};
        const double wideHi[3] = {hi[0] + reach, hi[1] + reach, hi[2] + reach};
        if (!sizes.mayHold(wideLo, wideHi, radius)) continue;
        if (!territory || territory->empty()) {
            gatherGeneration(lo, hi, s, g, accept, roots);
            continue;
        }
        for (std::uint32_t copy : territory->ownersIn(wideLo, wideHi)) {
            double o[3];
            territory->origin(copy, o);
            FloretSettings own = s;
            own.seed = counterBits(s.seed, 0xc09e5, copy);
            const double copyLo[3] = {lo[0] - o[0], lo[1] - o[1], lo[2] - o[2]};
            const double copyHi[3] = {hi[0] - o[0], hi[1] - o[1], hi[2] - o[2]};
            const auto inTerritory = [&](const double p[3], double r) {
                const double world[3] = {p[0] + o[0], p[1] + o[1], p[2] + o[2]};
                return territory->owner(world) == static_cast<std::int64_t>(copy) &&
                       accept(world, r);
            };
            const std::size_t first = roots.size();
            gatherGeneration(copyLo, copyHi, own, g, inTerritory, roots);
            for (std::size_t i = first; i < roots.size(); ++i)
                for (int a = 0; a < 3; ++a) roots[i].centre[a] += o[a];
        }
    }
    return roots;
}

}  // namespace

void growFlorets(openvdb::FloatGrid& grid, const FloretSettings& s, const CopyTerritory* territory,
                 const std::function<void()>& checkCancelled)
{
    if (s.radius == 0.0 || grid.empty()) return;
    checkFloretSettings(s);
    // Room for the lumps that stand out of the envelope: inactive voxels hold nothing. The
    // splats may leave values in voxels they switched off; dilation must not revive them.
    const double voxel = grid.voxelSize()[0];
    clearInactiveValues(grid);
    openvdb::tools::dilateActiveValues(grid.tree(),
                                       static_cast<int>(std::ceil(floretOverhang(s) / voxel)),
                                       openvdb::tools::NN_FACE_EDGE_VERTEX);
    grid.tree().voxelizeActiveTiles();  // dilation merges full leaves into tiles
    const openvdb::FloatGrid::Ptr sdf = openvdb::tools::fogToSdf(grid, kSurfaceValue, 1);
    if (checkCancelled) checkCancelled();
    if (!hasSurface(*sdf)) {
        openvdb::tools::pruneInactive(grid.tree());  // the dilation's zeros
        return;
    }
    const FloretSizes sizes(*sdf, s.radius);
    openvdb::tree::LeafManager<openvdb::FloatTree> leaves(grid.tree());
    leaves.foreach ([&](LeafT& leaf, std::size_t) {
        const openvdb::FloatGrid::ConstAccessor distance = sdf->getConstAccessor();
        // A root is part of the cloud where its centre lies in the layer under the envelope
        // and its size is the one the part's depth calls for.
        const auto acceptRoot = [&](const double p[3], double radius) {
            const openvdb::Coord at(static_cast<int>(std::lround(p[0] / voxel)),
                                    static_cast<int>(std::lround(p[1] / voxel)),
                                    static_cast<int>(std::lround(p[2] / voxel)));
            float d = 0.0f;
            if (!distance.probeValue(at, d)) return false;
            if (-d < kShallowestRoot * radius || -d > kDeepestRoot * radius) return false;
            const double scale = sizes.at(p);
            return scale >= radius && (radius == s.radius || scale < 2.0 * radius);
        };
        const openvdb::CoordBBox box = leaf.getNodeBoundingBox();
        const double lo[3] = {box.min()[0] * voxel, box.min()[1] * voxel, box.min()[2] * voxel};
        const double hi[3] = {box.max()[0] * voxel, box.max()[1] * voxel, box.max()[2] * voxel};
        const std::vector<FloretRoot> roots = rootsNear(lo, hi, s, sizes, territory, acceptRoot);
        float* values = leaf.buffer().data();
        for (auto on = leaf.getValueMask().beginOn(); on; ++on) {
            const openvdb::Index n = on.pos();
            const openvdb::Coord ijk = leaf.offsetToGlobalCoord(n);
            const float d = distance.getValue(ijk);
            // Deeper than the envelope sinks: the interior keeps its value.
            if (-d > s.radius + voxel) continue;
            const double world[3] = {ijk[0] * voxel, ijk[1] * voxel, ijk[2] * voxel};
            const double sink = sizes.at(world) *
                                smoothstep(kUnsunkNormalZ, kSunkNormalZ, normalZ(distance, ijk, d));
            // Metres inside the surface; past half a voxel the coverage is whole, so the
            // florets need not be walked further (or at all, inside the sunken envelope).
            const double body = -d - sink, whole = 0.5 * voxel;
            const double inside =
                body >= whole ? body : std::max(body, floretDepth(world, s, roots, -whole, whole));
            const double coverage = smoothstep(-whole, whole, inside);
            storeOrSwitchOff(leaf, values, n,
                             static_cast<float>(std::max(values[n], kSurfaceValue) * coverage));
        }
    });
    openvdb::tools::pruneInactive(grid.tree());
    if (checkCancelled) checkCancelled();
}

}  // namespace cg::algo
