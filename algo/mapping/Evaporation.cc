#include "algo/mapping/Evaporation.h"

#include <algorithm>

namespace cg::algo {

std::optional<float> condensationLevel(const CondensationView& c)
{
    std::optional<float> lowest;
    for (std::size_t i = 0; i < c.count; ++i)
        if (c.condensedFrame[i] >= 0 && (!lowest || c.condensedZ[i] < *lowest)) lowest = c.condensedZ[i];
    return lowest;
}

void dropCloudParticlesBelow(CloudParticleArrays& cloud, float zMin)
{
    // In place, front to back: the write index never passes the read index.
    const std::size_t n = cloud.levels.size();
    std::size_t kept = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (!(cloud.positions[3 * i + 2] >= zMin)) continue;
        if (kept != i) {
            std::copy_n(&cloud.positions[3 * i], 3, &cloud.positions[3 * kept]);
            cloud.levels[kept] = cloud.levels[i];
            cloud.sources[kept] = cloud.sources[i];
        }
        ++kept;
    }
    cloud.positions.shrink(3 * kept);
    cloud.levels.shrink(kept);
    cloud.sources.shrink(kept);
}

}  // namespace cg::algo
