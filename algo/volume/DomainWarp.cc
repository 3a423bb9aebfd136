#include "algo/volume/DomainWarp.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/Morphology.h>
#include <openvdb/tools/Prune.h>
#include <openvdb/tree/LeafManager.h>

#include "algo/noise/GradientNoise.h"
#include "algo/volume/LeafStore.h"

namespace cg::algo {

namespace {

using LeafT = openvdb::FloatTree::LeafNodeType;

/// Seeds of the warp's three components.
constexpr std::uint64_t kWarpSeed = 0x5741525046494c44ULL;

/// One tile of vector gradient noise, kCycles lattice cells a side, kTexelsPerCycle texels a
/// cell, built once per process: sampling it trilinearly costs eight loads an octave
/// instead of 24 hashes a component.
class WarpTexture {
public:
    static constexpr int kCycles = 6;
    static constexpr int kTexelsPerCycle = 8;
    static constexpr int kSize = kCycles * kTexelsPerCycle;

    WarpTexture() : mTexels(static_cast<std::size_t>(kSize * kSize * kSize) * 3)
    {
        std::size_t n = 0;
        for (int i = 0; i < kSize; ++i)
            for (int j = 0; j < kSize; ++j)
                for (int k = 0; k < kSize; ++k)
                    for (int a = 0; a < 3; ++a)
                        mTexels[n++] = static_cast<float>(std::clamp(
                            gradientNoise(static_cast<double>(i) / kTexelsPerCycle,
                                          static_cast<double>(j) / kTexelsPerCycle,
                                          static_cast<double>(k) / kTexelsPerCycle,
                                          kWarpSeed + static_cast<std::uint64_t>(a), kCycles),
                            -1.0, 1.0));
    }

    /// The noise vector at (u, v, w) lattice cells, trilinear between texels, wrapping.
    void sample(double u, double v, double w, double out[3]) const
    {
        const double p[3] = {u * kTexelsPerCycle, v * kTexelsPerCycle, w * kTexelsPerCycle};
        int lo[3], hi[3];
        double t[3];
        for (int a = 0; a < 3; ++a) {
            const double f = std::floor(p[a]);
            t[a] = p[a] - f;
            lo[a] = wrap(static_cast<long long>(f));
            hi[a] = wrap(static_cast<long long>(f) + 1);
        }
        out[0] = out[1] = out[2] = 0.0;
        for (int corner = 0; corner < 8; ++corner) {
            const int i = (corner & 4) ? hi[0] : lo[0], j = (corner & 2) ? hi[1] : lo[1],
                      k = (corner & 1) ? hi[2] : lo[2];
            const double weight = ((corner & 4) ? t[0] : 1.0 - t[0]) *
                                  ((corner & 2) ? t[1] : 1.0 - t[1]) *
                                  ((corner & 1) ? t[2] : 1.0 - t[2]);
            const float* texel =
                &mTexels[3 * ((static_cast<std::size_t>(i) * kSize + static_cast<std::size_t>(j)) *
                                  kSize +
                              static_cast<std::size_t>(k))];
            for (int a = 0; a < 3; ++a) out[a] += weight * texel[a];
        }
    }

private:
    static int wrap(long long i) { return static_cast<int>(((i % kSize) + kSize) % kSize); }
    std::vector<float> mTexels;
};

const WarpTexture& warpTexture()
{
    static const WarpTexture texture;
    return texture;
}

/// The largest displacement in voxels, rounded up: how far the active voxels must grow.
int reachInVoxels(const DomainWarpSettings& s, double voxel)
{
    return static_cast<int>(std::ceil(domainWarpReach(s) / voxel)) + 1;
}

/// The owners of the cells whose centres surround a leaf's voxels, looked up once per leaf,
/// and the warp at a voxel blended from them.
class LeafOwners {
public:
    LeafOwners(const openvdb::CoordBBox& box, double voxel, const CopyTerritory& territory)
        : mTerritory(territory), mCell(territory.cellSize())
    {
        for (int a = 0; a < 3; ++a) {
            mLo[a] = lowerCentre(box.min()[a] * voxel);
            mDim[a] = lowerCentre(box.max()[a] * voxel) + 2 - mLo[a];
        }
        mOwners.resize(static_cast<std::size_t>(mDim[0]) * static_cast<std::size_t>(mDim[1]) *
                       static_cast<std::size_t>(mDim[2]));
        std::size_t n = 0;
        for (int i = 0; i < mDim[0]; ++i)
            for (int j = 0; j < mDim[1]; ++j)
                for (int k = 0; k < mDim[2]; ++k)
                    mOwners[n++] = territory.ownerOfCell(mLo[0] + i, mLo[1] + j, mLo[2] + k);
    }

    /// The warp at world point x: the owners' warps, each in its copy's coordinates,
    /// weighted by the trilinear weights of the corners they own. World coordinates where
    /// no corner has an owner.
    void warpAt(const double x[3], const DomainWarpSettings& s, double w[3]) const
    {
        int base[3];
        double t[3];
        for (int a = 0; a < 3; ++a) {
            const double g = x[a] / mCell - 0.5;
            base[a] = static_cast<int>(std::floor(g));
            t[a] = g - base[a];
        }
        std::int64_t owners[8];
        double weights[8];
        int distinct = 0;
        double total = 0.0;
        for (int corner = 0; corner < 8; ++corner) {
            const int c[3] = {(corner >> 2) & 1, (corner >> 1) & 1, corner & 1};
            const std::int64_t owner = ownerAt(base[0] + c[0], base[1] + c[1], base[2] + c[2]);
            if (owner < 0) continue;
            double weight = 1.0;
            for (int a = 0; a < 3; ++a) weight *= c[a] ? t[a] : 1.0 - t[a];
            int d = 0;
            while (d < distinct && owners[d] != owner) ++d;
            if (d == distinct) {
                owners[distinct] = owner;
                weights[distinct++] = 0.0;
            }
            weights[d] += weight;
            total += weight;
        }
        if (!(total > 0.0)) {
            domainWarpAt(x, s, w);
            return;
        }
        w[0] = w[1] = w[2] = 0.0;
        for (int d = 0; d < distinct; ++d) {
            double origin[3], local[3], part[3];
            mTerritory.origin(static_cast<std::uint32_t>(owners[d]), origin);
            for (int a = 0; a < 3; ++a) local[a] = x[a] - origin[a];
            domainWarpAt(local, s, part);
            for (int a = 0; a < 3; ++a) w[a] += weights[d] / total * part[a];
        }
    }

private:
    /// The cell whose centre is the nearest at or below x.
    int lowerCentre(double x) const { return static_cast<int>(std::floor(x / mCell - 0.5)); }

    std::int64_t ownerAt(int i, int j, int k) const
    {
        i -= mLo[0];
        j -= mLo[1];
        k -= mLo[2];
        const auto at = [](int v) { return static_cast<std::size_t>(v); };
        return mOwners[(at(i) * at(mDim[1]) + at(j)) * at(mDim[2]) + at(k)];
    }

    const CopyTerritory& mTerritory;
    double mCell;
    int mLo[3] = {0, 0, 0}, mDim[3] = {0, 0, 0};
    std::vector<std::int64_t> mOwners;
};

/// The voxels whose every sample lies where the source is full (1): the full voxels eroded
/// by the reach. They stay 1 whatever the warp, so their noise is not evaluated.
openvdb::FloatTree::Ptr fullInterior(const openvdb::FloatGrid& source, int reach)
{
    auto interior = std::make_shared<openvdb::FloatTree>(source.tree());
    openvdb::tree::LeafManager<openvdb::FloatTree> leaves(*interior);
    leaves.foreach ([](LeafT& leaf, std::size_t) {
        for (auto on = leaf.beginValueOn(); on; ++on)
            if (!(*on >= 1.0f)) on.setValueOff();
    });
    openvdb::tools::erodeActiveValues(*interior, reach, openvdb::tools::NN_FACE_EDGE_VERTEX,
                                      openvdb::tools::IGNORE_TILES);
    return interior;
}

}  // namespace

void checkDomainWarpSettings(const DomainWarpSettings& s)
{
    if (!(s.amplitude >= 0.0) || !std::isfinite(s.amplitude))
        throw std::invalid_argument("domain warp: amplitude must be >= 0");
    if (!(s.wavelength > 0.0) || !std::isfinite(s.wavelength))
        throw std::invalid_argument("domain warp: wavelength must be > 0");
    if (s.octaves < 1 || s.octaves > 8)
        throw std::invalid_argument("domain warp: octaves must lie in 1..8");
    if (!(s.roughness > 0.0 && s.roughness <= 1.0))
        throw std::invalid_argument("domain warp: roughness must lie in (0, 1]");
}

double domainWarpReach(const DomainWarpSettings& s)
{
    double sum = 0.0, weight = 1.0;
    for (int o = 0; o < s.octaves; ++o, weight *= s.roughness) sum += weight;
    return s.amplitude * sum;
}

void domainWarpAt(const double x[3], const DomainWarpSettings& s, double w[3])
{
    const WarpTexture& texture = warpTexture();
    w[0] = w[1] = w[2] = 0.0;
    double frequency = 1.0 / s.wavelength, weight = s.amplitude;
    for (int o = 0; o < s.octaves; ++o, frequency *= 2.0, weight *= s.roughness) {
        // Each octave reads the tile at its own shift and with its axes rotated, so the
        // octaves' tiles and lattice points do not line up.
        const double shift = 1.37 * (o + 1);
        const double p[3] = {x[0] * frequency + shift, x[1] * frequency + 2.0 * shift,
                             x[2] * frequency + 3.0 * shift};
        double n[3];
        texture.sample(p[o % 3], p[(o + 1) % 3], p[(o + 2) % 3], n);
        for (int a = 0; a < 3; ++a) w[a] += weight * n[(a + o) % 3];
    }
    // Shortened where it would pass the reach, so the reach is a true bound with the
    // components summed as a vector.
    const double length = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    const double reach = domainWarpReach(s);
    if (length > reach)
        for (int a = 0; a < 3; ++a) w[a] *= reach / length;
}

void warpVolume(openvdb::FloatGrid& grid, const CopyTerritory* territory,
                const DomainWarpSettings& s, const std::function<void()>& checkCancelled)
{
    checkDomainWarpSettings(s);
    if (s.amplitude == 0.0 || grid.empty()) return;
    const double voxel = grid.voxelSize()[0];
    const openvdb::FloatGrid::ConstPtr source = grid.deepCopy();
    const int reach = reachInVoxels(s, voxel);
    const openvdb::FloatTree::ConstPtr interior = fullInterior(*source, reach);
    openvdb::tools::dilateActiveValues(grid.tree(), reach, openvdb::tools::NN_FACE_EDGE_VERTEX,
                                       openvdb::tools::EXPAND_TILES);
    if (checkCancelled) checkCancelled();
    openvdb::tree::LeafManager<openvdb::FloatTree> leaves(grid.tree());
    leaves.foreach ([&](LeafT& leaf, std::size_t) {
        std::optional<LeafOwners> owners;
        if (territory) owners.emplace(leaf.getNodeBoundingBox(), voxel, *territory);
        auto accessor = source->getConstUnsafeAccessor();
        openvdb::tree::ValueAccessor<const openvdb::FloatTree, false> inside(*interior);
        float* values = leaf.buffer().data();
        for (auto on = leaf.getValueMask().beginOn(); on; ++on) {
            const openvdb::Index n = on.pos();
            const openvdb::Coord ijk = leaf.offsetToGlobalCoord(n);
            if (inside.isValueOn(ijk)) continue;  // full, and every sample with it
            const double x[3] = {ijk.x() * voxel, ijk.y() * voxel, ijk.z() * voxel};
            double w[3];
            if (owners)
                owners->warpAt(x, s, w);
            else
                domainWarpAt(x, s, w);
            const openvdb::Vec3d at(ijk.x() + w[0] / voxel, ijk.y() + w[1] / voxel,
                                    ijk.z() + w[2] / voxel);
            float v = 0.0f;
            openvdb::tools::BoxSampler::sample(accessor, at, v);
            storeOrSwitchOff(leaf, values, n, v);
        }
    });
    openvdb::tools::pruneInactive(grid.tree());
    if (checkCancelled) checkCancelled();
}

}  // namespace cg::algo
