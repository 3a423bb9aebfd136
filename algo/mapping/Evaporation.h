#pragma once
/// Cloud particles under the condensation level would evaporate (ours; the paper keeps every
/// mapped particle): the primitive's copies hang below their origins, and a level 1 origin is
/// a condensation particle, so a copy's lower half lies under the cloud base.

#include <cstdint>
#include <optional>
#include <vector>

#include "algo/mapping/Mapping.h"

namespace cg::algo {

/// The condensation level at this frame: the lowest height at which a condensation particle
/// condensed (each condenses at its own level, which a moisture map or a sounding varies);
/// nullopt while nothing has condensed.
std::optional<float> condensationLevel(const CondensationView& c);

/// Keeps the particles whose height is at least zMin, in their order (levels and sources
/// with them), and shrinks the arrays to them.
void dropCloudParticlesBelow(CloudParticleArrays& cloud, float zMin);

/// Where chunkAbove copies the particles it keeps; reused from chunk to chunk.
struct KeptParticles {
    std::vector<float> positions;
    std::vector<std::uint8_t> levels;
    std::vector<std::uint32_t> sources;
    std::vector<float> velocities;
    std::vector<std::uint32_t> ids;
};

/// The same for one chunk of forEachCloudChunk: its particles whose height is at least zMin,
/// in their order, copied into `kept` (levels, sources, velocities and ids too when the chunk
/// has them). The result points into `kept`; its `first` stays the chunk's, which names the
/// chunk.
CloudChunk chunkAbove(const CloudChunk& chunk, float zMin, KeptParticles& kept);

}  // namespace cg::algo
