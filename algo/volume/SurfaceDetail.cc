#include "algo/volume/SurfaceDetail.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include <openvdb/tools/Prune.h>
#include <openvdb/tree/LeafManager.h>

#include "algo/noise/PerlinWorley.h"
#include "algo/volume/CopyOriginField.h"

namespace cg::algo {

namespace {

using LeafT = openvdb::FloatTree::LeafNodeType;

/// v remapped from [e, 1] to [0, 1]; 0 below e.
float erode(float v, float e)
{
    if (e >= 1.0f) return 0.0f;
    return std::max(0.0f, (v - e) / (1.0f - e));
}

}  // namespace

namespace {

void checkSettings(const SurfaceDetailSettings& s)
{
    if (!(s.amplitude >= 0.0 && s.amplitude <= 1.0))
        throw std::invalid_argument("surface detail: amplitude must lie in [0, 1]");
    if (!(s.frequency > 0.0) || !std::isfinite(s.frequency))
        throw std::invalid_argument("surface detail: frequency must be > 0");
    if (s.octaves < 1 || s.octaves > 8)
        throw std::invalid_argument("surface detail: octaves must lie in 1..8");
}

}  // namespace

double copyOriginCellSize(double radius, double voxelSize)
{
    return std::max(2.0 * radius, voxelSize);
}

void erodeSurface(openvdb::FloatGrid& grid, const DetailParticles& particles, double radius,
                  const SurfaceDetailSettings& s, const std::function<void()>& checkCancelled)
{
    checkSettings(s);
    if (!(radius > 0.0)) throw std::invalid_argument("surface detail: radius must be > 0");
    if (s.amplitude == 0.0 || grid.empty()) return;
    std::optional<CopyOriginField> field;
    if (particles.copyOrigins != nullptr)
        field.emplace(particles.xyz, particles.sources, particles.count, particles.copyOrigins,
                      particles.copyCount, copyOriginCellSize(radius, grid.voxelSize()[0]));
    if (checkCancelled) checkCancelled();
    erodeSurface(grid, field ? &*field : nullptr, s, checkCancelled);
}

void erodeSurface(openvdb::FloatGrid& grid, const CopyOriginField* field,
                  const SurfaceDetailSettings& s, const std::function<void()>& checkCancelled)
{
    checkSettings(s);
    if (s.amplitude == 0.0 || grid.empty()) return;
    const double voxel = grid.voxelSize()[0];
    const auto amplitude = static_cast<float>(s.amplitude);
    // The least erosion any noise value gives: a voxel at or below it erodes to nothing
    // whatever the noise is there (v <= e), so its noise is not evaluated. The roundings
    // are monotone, so the float e of any noise n <= the bound is at least this.
    const float leastErosion = amplitude * (1.0f - perlinWorleyUpperBound());
    openvdb::tree::LeafManager<openvdb::FloatTree> leaves(grid.tree());
    leaves.foreach ([&](LeafT& leaf, std::size_t) {
        constexpr int kDim = static_cast<int>(LeafT::DIM);
        const openvdb::Coord corner = leaf.origin();
        std::optional<CopyOriginField::Block> block;
        if (field) {
            const openvdb::CoordBBox box = leaf.getNodeBoundingBox();
            double lo[3], hi[3];
            for (int a = 0; a < 3; ++a) {
                lo[a] = box.min()[a] * voxel;
                hi[a] = box.max()[a] * voxel;
            }
            block = field->block(lo, hi);
        }
        // Per axis, the leaf's voxel coordinates in metres and their places among the copy
        // origin cells: found once per coordinate, not once per voxel.
        double metres[3][kDim];
        CopyOriginField::Block::AxisPlace places[3][kDim];
        for (int a = 0; a < 3; ++a)
            for (int l = 0; l < kDim; ++l) {
                metres[a][l] = (corner[a] + l) * voxel;
                if (block) places[a][l] = block->place(a, metres[a][l]);
            }
        float* values = leaf.buffer().data();
        // Switching the current voxel off does not disturb the iteration, which moves on
        // from the next bit.
        for (auto on = leaf.getValueMask().beginOn(); on; ++on) {
            const openvdb::Index n = on.pos();
            const float v = values[n];
            if (!(v < 1.0f)) continue;  // the interior keeps its density
            if (v <= leastErosion) {
                values[n] = 0.0f;
                leaf.setValueOff(n);
                continue;
            }
            const int i = static_cast<int>(n >> (2 * LeafT::LOG2DIM));
            const int j = static_cast<int>((n >> LeafT::LOG2DIM) & (kDim - 1));
            const int k = static_cast<int>(n & (kDim - 1));
            double x[3] = {metres[0][i], metres[1][j], metres[2][k]};
            double origin[3] = {0.0, 0.0, 0.0};
            // Every voxel a splat reached has an origin; a grid changed since (filtered,
            // combined) may have others, which keep world coordinates.
            if (block) {
                const CopyOriginField::Block::AxisPlace at[3] = {places[0][i], places[1][j],
                                                                 places[2][k]};
                if (!block->origin(at, origin)) origin[0] = origin[1] = origin[2] = 0.0;
            }
            for (int a = 0; a < 3; ++a) x[a] -= origin[a];
            const float e = amplitude * (1.0f - perlinWorleyFbm(x, s.frequency, s.octaves));
            const float eroded = erode(v, e);
            if (eroded > 0.0f) {
                values[n] = eroded;
            } else {
                values[n] = 0.0f;
                leaf.setValueOff(n);  // the background, inactive: only sparser
            }
        }
    });
    openvdb::tools::pruneInactive(grid.tree());  // leaves eroded away entirely
    if (checkCancelled) checkCancelled();
}

}  // namespace cg::algo
