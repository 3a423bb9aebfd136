#include "algo/mapping/Evaporation.h"

#include <algorithm>

namespace cg::algo {

std::optional<float> condensationLevel(const CondensationView& c)
{
    std::optional<float> lowest;
    for (std::size_t i = 0; i < c.count; ++i)
        if (c.condensedFrame[i] >= 0 && (!lowest || c.condensedZ[i] < *lowest))
            lowest = c.condensedZ[i];
    return lowest;
}

namespace {

/// A particle at height z stays; NaN heights go.
bool survives(float z, float zMin) { return z >= zMin; }

}  // namespace

void dropCloudParticlesBelow(CloudParticleArrays& cloud, float zMin)
{
    // In place, front to back: the write index never passes the read index.
    const std::size_t n = cloud.levels.size();
    std::size_t kept = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (!survives(cloud.positions[3 * i + 2], zMin)) continue;
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

CloudChunk chunkAbove(const CloudChunk& chunk, float zMin, KeptParticles& kept)
{
    kept.positions.clear();
    kept.levels.clear();
    kept.sources.clear();
    kept.velocities.clear();
    kept.ids.clear();
    for (std::uint64_t i = 0; i < chunk.count; ++i) {
        if (!survives(chunk.positions[3 * i + 2], zMin)) continue;
        kept.positions.insert(kept.positions.end(), chunk.positions + 3 * i,
                              chunk.positions + 3 * i + 3);
        if (chunk.levels) kept.levels.push_back(chunk.levels[i]);
        if (chunk.sources) kept.sources.push_back(chunk.sources[i]);
        if (chunk.velocities)
            kept.velocities.insert(kept.velocities.end(), chunk.velocities + 3 * i,
                                   chunk.velocities + 3 * i + 3);
        if (chunk.ids) kept.ids.push_back(chunk.ids[i]);
    }
    CloudChunk out = chunk;
    out.count = kept.positions.size() / 3;
    out.positions = kept.positions.data();
    out.levels = chunk.levels ? kept.levels.data() : nullptr;
    out.sources = chunk.sources ? kept.sources.data() : nullptr;
    out.velocities = chunk.velocities ? kept.velocities.data() : nullptr;
    out.ids = chunk.ids ? kept.ids.data() : nullptr;
    return out;
}

}  // namespace cg::algo
