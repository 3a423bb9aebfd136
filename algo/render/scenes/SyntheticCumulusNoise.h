#pragma once
/// The synthetic cumulus's billow noise, built on the deterministic gradient noise, so
/// rasterisation order and thread count never change the cloud.

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "algo/noise/GradientNoise.h"

namespace cg::algo {

/// "Billow" fBm: Σ 0.5^o |noise(2^o p / scale)| over `octaves`, normalised to about [0, 1];
/// the absolute value gives the rounded, puffy features of cumulus turrets.
inline double billowNoise(double x, double y, double z, double scale, int octaves,
                          std::uint64_t seed)
{
    double sum = 0.0, norm = 0.0, amp = 1.0, f = 1.0 / scale;
    for (int o = 0; o < octaves; ++o) {
        sum += amp * std::abs(gradientNoise(x * f, y * f, z * f, seed + std::uint64_t(o)));
        norm += amp;
        amp *= 0.5;
        f *= 2.0;
    }
    return std::min(1.0, 1.6 * sum / norm);  // |noise| averages about 0.3
}

}  // namespace cg::algo
