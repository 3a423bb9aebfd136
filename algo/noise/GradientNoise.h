#pragma once
/// Deterministic 3D gradient noise: a pure function of position and seed (lattice gradients
/// from the counter-based hash), so evaluation order and thread count never change a result.

#include <cmath>
#include <cstdint>

#include "algo/CounterRandom.h"

namespace cg::algo {

/// Perlin-style gradient noise (quintic fade, 12 edge gradients), about [−1, 1], lattice
/// spacing 1. With period > 0 the lattice wraps every `period` cells, so the noise tiles.
inline double gradientNoise(double x, double y, double z, std::uint64_t seed,
                            std::int64_t period = 0)
{
    const double fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
    const auto ix = static_cast<std::int64_t>(fx);
    const auto iy = static_cast<std::int64_t>(fy);
    const auto iz = static_cast<std::int64_t>(fz);
    const double rx = x - fx, ry = y - fy, rz = z - fz;
    const auto fade = [](double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); };
    const double u = fade(rx), v = fade(ry), w = fade(rz);
    const auto wrap = [period](std::int64_t i) {
        return period > 0 ? ((i % period) + period) % period : i;
    };
    const auto corner = [&](int dx, int dy, int dz) {
        const std::uint64_t h =
            mix64(mix64(mix64(seed ^ static_cast<std::uint64_t>(wrap(ix + dx))) ^
                        static_cast<std::uint64_t>(wrap(iy + dy))) ^
                  static_cast<std::uint64_t>(wrap(iz + dz)));
        const double px = rx - dx, py = ry - dy, pz = rz - dz;
        switch (h % 12) {  // the 12 edge directions of a cube
            case 0:
                return px + py;
            case 1:
                return -px + py;
            case 2:
                return px - py;
            case 3:
                return -px - py;
            case 4:
                return px + pz;
            case 5:
                return -px + pz;
            case 6:
                return px - pz;
            case 7:
                return -px - pz;
            case 8:
                return py + pz;
            case 9:
                return -py + pz;
            case 10:
                return py - pz;
            default:
                return -py - pz;
        }
    };
    const auto lerp = [](double a, double b, double t) { return a + (b - a) * t; };
    return lerp(lerp(lerp(corner(0, 0, 0), corner(1, 0, 0), u),
                     lerp(corner(0, 1, 0), corner(1, 1, 0), u), v),
                lerp(lerp(corner(0, 0, 1), corner(1, 0, 1), u),
                     lerp(corner(0, 1, 1), corner(1, 1, 1), u), v),
                w);
}

}  // namespace cg::algo
