#include "algo/volume/SurfaceDetail.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include <openvdb/tools/Prune.h>
#include <openvdb/tree/LeafManager.h>

#include "algo/noise/PerlinWorley.h"
#include "algo/volume/CopyOriginField.h"
#include "algo/volume/LeafCopyCoordinates.h"
#include "algo/volume/LeafStore.h"

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
        const LeafCopyCoordinates<LeafT> coordinates(leaf, voxel, field);
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
            double x[3];
            coordinates.at(n, x);
            const float e = amplitude * (1.0f - perlinWorleyFbm(x, s.frequency, s.octaves));
            storeOrSwitchOff(leaf, values, n, erode(v, e));
        }
    });
    openvdb::tools::pruneInactive(grid.tree());  // leaves eroded away entirely
    if (checkCancelled) checkCancelled();
}

}  // namespace cg::algo
