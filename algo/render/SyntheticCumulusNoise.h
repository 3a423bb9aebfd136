#pragma once
/// Deterministic 3D gradient noise for the synthetic cumulus: a pure function of position and
/// seed (lattice gradients from the counter-based hash), so rasterisation order and thread
/// count never change the cloud.

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "algo/CounterRandom.h"

namespace cg::algo {

/// Perlin-style gradient noise (quintic fade, 12 edge gradients), about [−1, 1], period 1.
inline double gradientNoise(double x, double y, double z, std::uint64_t seed)
{
    const double fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
    const auto ix = static_cast<std::int64_t>(fx);
    const auto iy = static_cast<std::int64_t>(fy);
    const auto iz = static_cast<std::int64_t>(fz);
    const double rx = x - fx, ry = y - fy, rz = z - fz;
    const auto fade = [](double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); };
    const double u = fade(rx), v = fade(ry), w = fade(rz);
    const auto corner = [&](int dx, int dy, int dz) {
        const std::uint64_t h =
            mix64(mix64(mix64(seed ^ static_cast<std::uint64_t>(ix + dx)) ^
                        static_cast<std::uint64_t>(iy + dy)) ^
                  static_cast<std::uint64_t>(iz + dz));
        const double px = rx - dx, py = ry - dy, pz = rz - dz;
        switch (h % 12) {  // the 12 edge directions of a cube
        case 0: return px + py;
        case 1: return -px + py;
        case 2: return px - py;
        case 3: return -px - py;
        case 4: return px + pz;
        case 5: return -px + pz;
        case 6: return px - pz;
        case 7: return -px - pz;
        case 8: return py + pz;
        case 9: return -py + pz;
        case 10: return py - pz;
        default: return -py - pz;
        }
    };
    const auto lerp = [](double a, double b, double t) { return a + (b - a) * t; };
    return lerp(lerp(lerp(corner(0, 0, 0), corner(1, 0, 0), u),
                     lerp(corner(0, 1, 0), corner(1, 1, 0), u), v),
                lerp(lerp(corner(0, 0, 1), corner(1, 0, 1), u),
                     lerp(corner(0, 1, 1), corner(1, 1, 1), u), v),
                w);
}

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
