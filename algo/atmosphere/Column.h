#pragma once
/// The environment as tables by height above the ground, sampled at even steps, so the
/// per-particle steps look values up instead of searching a sounding's levels (docs/atmosphere.md).

#include <cstddef>
#include <vector>

#include "algo/atmosphere/Profile.h"
#include "algo/atmosphere/Wind.h"

namespace cg::algo {

struct EnvironmentColumn {
    double step = 10.0;  ///< metres between samples
    /// Sample k is at height k * step above the ground. Empty without a profile (the paper's
    /// Eq. 9 is then used instead); the wind tables are empty when the wind is calm.
    std::vector<float> temperature;  ///< C
    std::vector<float> dewpoint;     ///< C
    std::vector<float> pressure;     ///< hPa
    std::vector<float> windEast;     ///< m/s
    std::vector<float> windNorth;    ///< m/s

    /// Linear between samples, held at the end values below 0 and above the top.
    float at(const std::vector<float>& table, float heightAboveGround) const
    {
        const float s = heightAboveGround * static_cast<float>(1.0 / step);
        const float last = static_cast<float>(table.size() - 1);
        const float clamped = s < 0.0f ? 0.0f : (s > last ? last : s);
        auto i = static_cast<std::size_t>(clamped);
        if (i + 1 >= table.size()) i = table.size() - 2;
        const float w = clamped - static_cast<float>(i);
        return table[i] + w * (table[i + 1] - table[i]);
    }
};

/// The most samples one table may hold; a deeper profile is sampled more coarsely.
constexpr std::size_t kMaxColumnSamples = 10001;

/// Samples `profile` (may be null: no environment tables) and `wind` every 10 m (coarser
/// when the deeper of the two spans more than kMaxColumnSamples) from the ground (the
/// profile's first level; heights of `wind` are already above the ground) to the top.
EnvironmentColumn sampleColumn(const EnvironmentProfile* profile, const WindProfile& wind);

}  // namespace cg::algo
