#pragma once
/// The mapper's internals that its three sources share, not part of its API (Mapping.h):
/// Mapping.cc defines them beside the formulas they belong to; MappingSources.cc (source
/// selection) and MappingGeneration.cc (chunked generation) call them.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "algo/mapping/Mapping.h"

namespace cg::algo::mapping {

/// The counter-based streams the mapper draws from, kept together so that no two coincide.
/// Levels use streams below 2^40: (L << 32 | t) picks the candidates of level L at frame t.
/// The stream of the copies' phases.
inline constexpr std::uint64_t kPhaseStream = std::uint64_t{1} << 40;
/// The streams of Eq. 15's draws of a parent source and of a particle in it, one per
/// (level, frame) below each.
inline constexpr std::uint64_t kParentStream = std::uint64_t{1} << 41;
inline constexpr std::uint64_t kParticleStream = std::uint64_t{1} << 42;
/// The stream of the sources' primitives.
inline constexpr std::uint64_t kPrimitiveStream = std::uint64_t{1} << 43;

/// Refuses a library that is not the one the settings' table was made with.
void checkLibrary(const PrimitiveLibrary& lib, const MappingSettings& s);

/// The primitive source j plays.
inline const PrimitiveView& viewOf(const PrimitiveLibrary& lib, std::size_t j,
                                   const MappingSettings& s)
{
    return lib.views[primitiveOf(j, s)];
}

/// Each primitive's drift (primitiveDrift), by its index in the library.
using Drifts = std::vector<std::array<float, 3>>;
Drifts drifts(const PrimitiveLibrary& lib);

/// Eq. 10 for one particle: fluid id i of the copy of `src` that stands at `copyAt` (its
/// copyOrigin), with the arithmetic of sourceSlice (copyAt + r P_f), so a child's origin is bit
/// for bit its parent particle.
void cloudParticlePosition(const Source& src, const float* copyAt, std::uint32_t i, int frame,
                           const PrimitiveView& p, const MappingSettings& s, float out[3]);

/// Per source, 3 floats each: its origin P_s[L, j](t) (Eq. 12) and where its copy stands
/// (copyOrigin: the origin plus its drift); zero for sources that start after t.
struct Origins {
    std::vector<float> origin;
    std::vector<float> copy;
};

/// Origins in one pass in table order (parents precede children): a child's origin is its
/// parent's particle, read off the parent's copy origin computed just before.
Origins originsWithDrift(const SourceTable& table, int frame, const CondensationView& c,
                         const PrimitiveLibrary& lib, const MappingSettings& s,
                         const Drifts& drift);

}  // namespace cg::algo::mapping
