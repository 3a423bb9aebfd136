#include "algo/render/scenes/SyntheticCumulus.h"

#include <algorithm>
#include <cmath>

#include "algo/CounterRandom.h"

namespace cg::algo {

namespace {

constexpr double kTwoPi = 6.283185307179586;

/// Uniform in [lo, hi) from the counter (blob, draw).
double uniform(std::uint64_t seed, std::uint64_t blob, std::uint64_t draw, double lo, double hi)
{
    return lo + (hi - lo) * counterUniform(seed, blob, draw);
}

}  // namespace

std::vector<CumulusBlob> cumulusBlobs(const SyntheticCumulusSettings& s)
{
    std::vector<CumulusBlob> blobs;
    const double rb = s.baseRadius;
    std::uint64_t id = 0;

    // Level 0: one central blob and a ring of six, centres half a radius above the base so
    // that the flat cut leaves a broad, flat bottom.
    constexpr int kBase = 7;
    for (int i = 0; i < kBase; ++i, ++id) {
        const double r = rb * (i == 0 ? 0.55 : uniform(s.seed, id, 0, 0.36, 0.46));
        const double a = kTwoPi * (i - 1) / (kBase - 1) + uniform(s.seed, id, 1, -0.3, 0.3);
        const double d = i == 0 ? 0.0 : rb * uniform(s.seed, id, 2, 0.5, 0.62);
        blobs.push_back({d * std::cos(a), d * std::sin(a) * 0.8,
                         s.baseHeight + r * uniform(s.seed, id, 3, 0.35, 0.55), r});
    }

    // Higher levels: children on the upper side of their parent, pulled toward the cloud's
    // axis so the pile narrows into a dome or tower.
    std::size_t first = 0, last = blobs.size();
    for (int level = 1; level < s.levels; ++level) {
        for (std::size_t p = first; p < last; ++p) {
            const CumulusBlob parent = blobs[p];
            for (int c = 0; c < s.children; ++c, ++id) {
                const double a = kTwoPi * counterUniform(s.seed, id, 0);
                const double up = uniform(s.seed, id, 1, 0.35, 0.95);  // z of the direction
                const double h = std::sqrt(1.0 - up * up);
                double dx = h * std::cos(a), dy = h * std::sin(a);
                // Inward pull, stronger for blobs far from the axis.
                dx -= 0.6 * parent.x / rb;
                dy -= 0.6 * parent.y / rb;
                const double dz = up * s.towerHeight;
                const double len = std::sqrt(dx * dx + dy * dy + dz * dz);
                const double dist = parent.radius * uniform(s.seed, id, 2, 0.55, 0.85);
                const double r = parent.radius * uniform(s.seed, id, 3, 0.55, 0.7);
                blobs.push_back({parent.x + dx / len * dist, parent.y + dy / len * dist,
                                 parent.z + dz / len * dist, r});
            }
        }
        first = last;
        last = blobs.size();
    }
    return blobs;
}

std::uint64_t cumulusVoxelBound(const SyntheticCumulusSettings& s)
{
    // Each level rises by at most 0.85 × the parent's radius (≤ 0.7 of the level below)
    // times the stretch; children never leave the parent's bounding sphere by more than that.
    double reach = s.baseRadius * 0.62 + s.baseRadius * 0.55;  // horizontal
    double top = s.baseRadius * 1.1;
    double r = s.baseRadius * 0.55;
    for (int level = 1; level < s.levels; ++level) {
        top += r * 0.85 * std::max(1.0, s.towerHeight) + r * 0.7;
        reach += r * 0.85 * 1.6;
        r *= 0.7;
    }
    const double n = 2.0 * reach / s.voxelSize + 2.0;
    const double nz = top / s.voxelSize + 2.0;
    const double total = n * n * nz;
    return total > 1.8e19 ? ~std::uint64_t(0) : static_cast<std::uint64_t>(total);
}

}  // namespace cg::algo
