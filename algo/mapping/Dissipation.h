#pragma once
/// Clouds that dissipate (ours; the paper animates growth only): once a cloud's thermal has
/// stopped feeding it, dry air entrained at its edges evaporates it from the outside in.
///
/// A cloud is a level 1 copy with every copy grown on it (its descendants). Its supply ends
/// when its own primitive has played to its last frame (the thermal's growth is over); after
/// `hold` seconds it decays over a time proportional to its size, decayTime R / R0 (R its
/// scale, R0 the mapper's scaleCoefficient: the largest clouds take decayTime), as the
/// evaporation time of a cumulus grows with its size (small fair-weather cumulus live
/// minutes, large ones tens of minutes). At decay fraction f in [0, 1] a particle survives
/// while its distance from its copy's centre, in units of the copy's radius and jittered
/// per particle, is below 1 - f: the edges go first, and at f = 1 nothing is left. A copy of
/// level L counts L f (capped at 1): the turrets grown on a cloud go before its body, which
/// would otherwise leave small copies floating where the body has gone.
///
/// Ice lasts: with anvilBase > 0 a copy whose origin lies at or above anvilBase (the anvil's
/// glaciated outflow) counts L f / anvilLife instead, so the anvil outlives the tower that fed
/// it. Ice crystals in the dry air of the upper troposphere sublimate slowly and settle, so
/// anvils persist as cirrus for hours after their storm (Garrett et al. 2005 followed one for
/// three hours); the factor is ours.

#include <array>
#include <cstdint>
#include <vector>

#include "algo/mapping/Evaporation.h"
#include "algo/mapping/Mapping.h"

namespace cg::algo {

struct DissipationSettings {
    double hold = 120.0;       ///< s between the end of a cloud's growth and its decay (ours)
    double decayTime = 600.0;  ///< s for a cloud of scale R0 to evaporate (ours)
    double anvilBase = 0.0;    ///< m above the ground: copies from here up last longer; 0: none
    double anvilLife = 4.0;    ///< how many times longer they take (>= 1; ours)
};

/// Throws std::invalid_argument naming the setting that is negative or not finite.
void checkDissipation(const DissipationSettings& d);

/// Per primitive frame, where a copy's centre is and how far its particles reach, in
/// primitive units: the centroid and the 95th percentile of the distance from it.
struct PrimitiveExtent {
    std::vector<std::array<float, 4>> frames;  ///< x, y, z, radius per frame
};
PrimitiveExtent primitiveExtent(const PrimitiveView& p);

/// Per source, the decay fraction f >= 0 of the cloud it belongs to at frame t: the share of
/// its decay time gone, 0 before it starts, 1 at its end and more after (a copy above the
/// anvil base reads it divided by anvilLife). Throws as checkDissipation does for unusable
/// settings.
std::vector<float> cloudDecay(const SourceTable& table, int frame, const PrimitiveLibrary& lib,
                              const MappingSettings& s, const DissipationSettings& d);

/// What chunkSurviving needs for a frame.
struct DissipationFrame {
    std::vector<float> decay;              ///< per source (cloudDecay)
    std::vector<PrimitiveExtent> extents;  ///< per primitive of the library
    const SourceTable* table = nullptr;
    const PrimitiveLibrary* library = nullptr;
    const MappingSettings* settings = nullptr;
    DissipationSettings dissipation;  ///< for the anvil's slower decay
    int frame = 0;
};

/// The chunk's particles that have not evaporated, in their order, copied into `kept` (as
/// chunkAbove does). The chunk must carry sources and copy origins.
CloudChunk chunkSurviving(const CloudChunk& chunk, const DissipationFrame& d, KeptParticles& kept);

}  // namespace cg::algo
