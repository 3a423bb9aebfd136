#pragma once
/// Condensation, pseudocode lines 9-14: vapour particles colder than the dew point become
/// condensation particles, for good. No engine includes.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace cg::algo {

struct CondensationState {
    std::vector<std::int32_t> condensedFrame;  ///< per particle: frame it condensed, -1 if not
    std::vector<float> condensedHeight;        ///< per particle: its z that frame; NaN if not
    std::int32_t firstFrame = -1;              ///< t_s[1]: the first condensation; -1 if none
    std::size_t count = 0;                     ///< condensation particles, N_v(t)
};

/// Frame `frame` from the previous frame's state (nullptr on the first frame): particle i
/// condenses when temperature[i] < dewPoint, at its height z[i], and a condensation particle
/// never turns back. Throws std::invalid_argument when the particle count differs from the
/// previous frame's.
CondensationState condenseStep(const CondensationState* previous, const float* temperature,
                               const float* z, std::size_t count, double dewPoint,
                               std::int32_t frame);

/// The same with a dew point per particle: particle i condenses when temperature[i] <
/// dewpoints[i].
CondensationState condenseStep(const CondensationState* previous, const float* temperature,
                               const float* dewpoints, const float* z, std::size_t count,
                               std::int32_t frame);

}  // namespace cg::algo
