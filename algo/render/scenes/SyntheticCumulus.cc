#include "algo/render/scenes/SyntheticCumulus.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "algo/render/scenes/SyntheticCumulusNoise.h"

namespace cg::algo {

namespace {

using Leaf = openvdb::FloatTree::LeafNodeType;
constexpr int kLeafDim = static_cast<int>(Leaf::DIM);
constexpr openvdb::Int32 kLeafMask = ~(kLeafDim - 1);  // rounds a coordinate down to its leaf

double smoothstep(double e0, double e1, double x)
{
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

/// Blob index bounds (voxel coordinates, inclusive).
openvdb::CoordBBox blobBox(const CumulusBlob& b, double voxel)
{
    const auto lo = [&](double c) { return static_cast<int>(std::floor((c - b.radius) / voxel)); };
    const auto hi = [&](double c) { return static_cast<int>(std::ceil((c + b.radius) / voxel)); };
    return {openvdb::Coord(lo(b.x), lo(b.y), lo(b.z)), openvdb::Coord(hi(b.x), hi(b.y), hi(b.z))};
}

}  // namespace

openvdb::FloatGrid::Ptr rasterizeCumulus(const std::vector<CumulusBlob>& blobs,
                                         const SyntheticCumulusSettings& s)
{
    openvdb::initialize();
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(s.voxelSize));
    const double voxel = s.voxelSize;
    const int baseIndex = static_cast<int>(std::floor(s.baseHeight / voxel));

    // The leaves any blob touches, above the base, sorted so the insertion order is fixed.
    std::vector<openvdb::CoordBBox> boxes;
    std::vector<openvdb::Coord> origins;
    for (const CumulusBlob& b : blobs) {
        openvdb::CoordBBox box = blobBox(b, voxel);
        box.min().z() = std::max(box.min().z(), baseIndex);
        boxes.push_back(box);
        if (box.empty()) continue;
        const openvdb::Coord l0 = box.min() & kLeafMask;
        const openvdb::Coord l1 = box.max() & kLeafMask;
        for (int i = l0.x(); i <= l1.x(); i += kLeafDim)
            for (int j = l0.y(); j <= l1.y(); j += kLeafDim)
                for (int k = l0.z(); k <= l1.z(); k += kLeafDim) origins.emplace_back(i, j, k);
    }
    std::sort(origins.begin(), origins.end());
    origins.erase(std::unique(origins.begin(), origins.end()), origins.end());

    std::vector<std::unique_ptr<Leaf>> leaves(origins.size());
    const double soft = std::max(1e-3, s.edgeSoftness);
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, origins.size(), 4),
        [&](const tbb::blocked_range<std::size_t>& range) {
            std::vector<std::size_t> near;
            for (std::size_t li = range.begin(); li != range.end(); ++li) {
                const openvdb::CoordBBox leafBox =
                    openvdb::CoordBBox::createCube(origins[li], kLeafDim);
                near.clear();
                for (std::size_t b = 0; b < blobs.size(); ++b)
                    if (boxes[b].hasOverlap(leafBox)) near.push_back(b);
                auto leaf = std::make_unique<Leaf>(origins[li], 0.0f, false);
                bool any = false;
                for (auto it = leafBox.begin(); it; ++it) {
                    const openvdb::Coord ijk = *it;
                    const double x = ijk.x() * voxel, y = ijk.y() * voxel, z = ijk.z() * voxel;
                    // Shape: summed soft spheres, 1 in each core, fading over `soft` of the radius.
                    double shape = 0.0;
                    for (const std::size_t b : near) {
                        const CumulusBlob& c = blobs[b];
                        const double dx = x - c.x, dy = y - c.y, dz = z - c.z;
                        const double d2 = dx * dx + dy * dy + dz * dz;
                        if (d2 >= c.radius * c.radius) continue;
                        shape += smoothstep(0.0, soft, 1.0 - std::sqrt(d2) / c.radius);
                        if (shape >= 1.0) break;
                    }
                    if (shape <= 0.0) continue;
                    shape = std::min(shape, 1.0);
                    // Erode the edges with billow noise: thin shape values vanish where the noise
                    // is high, the core (shape 1) stays; the base is cut flat over about a voxel.
                    double d = shape;
                    if (s.noiseAmplitude > 0.0) {
                        const double n = billowNoise(x, y, z, s.noiseScale, 4, s.seed * 0x9e37ull);
                        const double e = s.noiseAmplitude * n;
                        d = std::clamp((shape - e) / (1.0 - e + 1e-9), 0.0, 1.0);
                    }
                    d *= smoothstep(s.baseHeight - 0.5 * voxel, s.baseHeight + voxel, z);
                    const auto v = static_cast<float>(d * s.density);
                    if (v > 1e-4f) {
                        leaf->setValueOn(ijk, v);
                        any = true;
                    }
                }
                if (any) leaves[li] = std::move(leaf);
            }
        });

    auto& tree = grid->tree();
    for (auto& leaf : leaves)
        if (leaf) tree.addLeaf(leaf.release());
    return grid;
}

}  // namespace cg::algo
