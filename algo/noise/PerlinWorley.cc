#include "algo/noise/PerlinWorley.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <tbb/parallel_for.h>

#include "algo/CounterRandom.h"
#include "algo/noise/GradientNoise.h"

namespace cg::algo {

namespace {

constexpr int kSize = kPerlinWorleyTextureSize;
constexpr int kMask = kSize - 1;
constexpr int kCycles = kSize / kPerlinWorleyTexelsPerCycle;  // cycles across the texture
static_assert((kSize & kMask) == 0, "the texture wraps with a mask");
static_assert(kSize % kPerlinWorleyTexelsPerCycle == 0, "whole cycles tile");

constexpr std::uint64_t kWorleySeed = 0x5713a11d0f3e9c21ull;
constexpr std::uint64_t kPerlinSeed = 0x2b7e151628aed2a6ull;

/// A wrapping lattice of `cells` cells per axis with one feature point per cell, at a hashed
/// place inside it. The feature points are kept for the cells -1 .. cells on each axis (the
/// lattice and one wrapped cell around it), so a point in [0, cells)^3 finds its 27
/// neighbours without wrapping.
struct WorleyLattice {
    WorleyLattice(int cellsPerAxis, std::uint64_t seed)
        : cells(cellsPerAxis),
          padded(cellsPerAxis + 2),
          features(std::size_t(3) * padded * padded * padded)
    {
        for (int i = -1; i <= cells; ++i)
            for (int j = -1; j <= cells; ++j)
                for (int k = -1; k <= cells; ++k) {
                    std::uint64_t h = seed;
                    for (const int c : {i, j, k})
                        h = mix64(h ^ static_cast<std::uint64_t>(((c % cells) + cells) % cells));
                    double* f = &features[3 * index(i, j, k)];
                    const int c[3] = {i, j, k};
                    for (int a = 0; a < 3; ++a)
                        f[a] = c[a] + static_cast<double>((h >> (21 * a)) & 0x1fffff) * 0x1.0p-21;
                }
    }
    std::size_t index(int i, int j, int k) const
    {
        return (std::size_t(i + 1) * padded + std::size_t(j + 1)) * padded + std::size_t(k + 1);
    }
    /// The feature point of cell c, each of c's coordinates in -1 .. cells.
    const double* feature(int i, int j, int k) const { return &features[3 * index(i, j, k)]; }
    int cells;
    int padded;
    std::vector<double> features;
};

/// Worley's F1 in cell units at point p (in cells, inside [0, cells)^3) of the lattice: the
/// distance to the nearest feature point.
double worleyF1(const double p[3], const WorleyLattice& lattice)
{
    int base[3];
    for (int a = 0; a < 3; ++a) base[a] = static_cast<int>(std::floor(p[a]));
    double best = 1e30;
    for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dz = -1; dz <= 1; ++dz) {
                const double* f = lattice.feature(base[0] + dx, base[1] + dy, base[2] + dz);
                double d2 = 0.0;
                for (int a = 0; a < 3; ++a) {
                    const double d = f[a] - p[a];
                    d2 += d * d;
                }
                best = std::min(best, d2);
            }
    return std::sqrt(best);
}

/// The noise at point p in cycles (periodic with kCycles): the texel value of the header.
float perlinWorleyAt(const double p[3], const WorleyLattice& coarse, const WorleyLattice& fine)
{
    const auto billow = [&](int factor, const WorleyLattice& lattice) {
        const double q[3] = {p[0] * factor, p[1] * factor, p[2] * factor};
        return 1.0 - std::min(worleyF1(q, lattice), 1.0);
    };
    const double worley = 0.75 * billow(1, coarse) + 0.25 * billow(2, fine);
    const double perlin = 0.5 + 0.5 * gradientNoise(p[0], p[1], p[2], kPerlinSeed, kCycles);
    return static_cast<float>(std::clamp(0.7 * worley + 0.3 * perlin, 0.0, 1.0));
}

/// The texture, x-major: texel (i, j, k) at index (i kSize + j) kSize + k.
const std::vector<float>& texture()
{
    static const std::vector<float> texels = [] {
        std::vector<float> t(static_cast<std::size_t>(kSize) * kSize * kSize);
        const WorleyLattice coarse(kCycles, kWorleySeed), fine(2 * kCycles, kWorleySeed + 1);
        tbb::parallel_for(0, kSize, [&](int i) {
            for (int j = 0; j < kSize; ++j)
                for (int k = 0; k < kSize; ++k) {
                    const double p[3] = {static_cast<double>(i) / kPerlinWorleyTexelsPerCycle,
                                         static_cast<double>(j) / kPerlinWorleyTexelsPerCycle,
                                         static_cast<double>(k) / kPerlinWorleyTexelsPerCycle};
                    t[(static_cast<std::size_t>(i) * kSize + j) * kSize + k] =
                        perlinWorleyAt(p, coarse, fine);
                }
        });
        return t;
    }();
    return texels;
}

/// The trilinear sample of the texture `t` (see perlinWorleyTexel); inline, so the fractal
/// sum's octaves sample it without a call each.
inline float sampleTexture(const float* t, float u, float v, float w)
{
    const float fu = std::floor(u), fv = std::floor(v), fw = std::floor(w);
    const float tu = u - fu, tv = v - fv, tw = w - fw;
    // Wrapped lattice indices; the casts are exact for |coordinates| < 2^31.
    const int i0 = static_cast<int>(static_cast<std::int64_t>(fu) & kMask), i1 = (i0 + 1) & kMask;
    const int j0 = static_cast<int>(static_cast<std::int64_t>(fv) & kMask), j1 = (j0 + 1) & kMask;
    const int k0 = static_cast<int>(static_cast<std::int64_t>(fw) & kMask), k1 = (k0 + 1) & kMask;
    const auto at = [t](int i, int j, int k) {
        return t[(static_cast<std::size_t>(i) * kSize + j) * kSize + k];
    };
    const auto lerp = [](float a, float b, float s) { return a + s * (b - a); };
    const float x00 = lerp(at(i0, j0, k0), at(i0, j0, k1), tw);
    const float x01 = lerp(at(i0, j1, k0), at(i0, j1, k1), tw);
    const float x10 = lerp(at(i1, j0, k0), at(i1, j0, k1), tw);
    const float x11 = lerp(at(i1, j1, k0), at(i1, j1, k1), tw);
    return lerp(lerp(x00, x01, tv), lerp(x10, x11, tv), tu);
}

}  // namespace

float perlinWorleyTexel(float u, float v, float w)
{
    return sampleTexture(texture().data(), u, v, w);
}

float perlinWorleyUpperBound()
{
    static const float bound = [] {
        const std::vector<float>& t = texture();
        // A trilinear sample is a convex mix of texels: at most the largest, but for a few
        // float roundings of the three lerps, and the fractal sum is a weighted mean of
        // samples; 1e-6 is over ten times those roundings on values below 1.
        return *std::max_element(t.begin(), t.end()) + 1e-6f;
    }();
    return bound;
}

float perlinWorleyFbm(const double x[3], double frequency, int octaves)
{
    // Incommensurate shifts (texels), so the octaves' tiles never line up.
    constexpr double kShift[3] = {17.31, 41.07, 5.93};
    double sum = 0.0, norm = 0.0, amplitude = 1.0;
    double texelsPerMetre = frequency * kPerlinWorleyTexelsPerCycle;
    const float* t = texture().data();
    for (int o = 0; o < octaves; ++o) {
        // Coordinates reduced modulo the tile in double before the float sample: metres far
        // from the origin keep their sub-texel precision.
        float uvw[3];
        for (int a = 0; a < 3; ++a) {
            const double u = x[a] * texelsPerMetre + o * kShift[a];
            uvw[a] = static_cast<float>(u - kSize * std::floor(u / kSize));
        }
        sum += amplitude * sampleTexture(t, uvw[0], uvw[1], uvw[2]);
        norm += amplitude;
        amplitude *= 0.5;
        texelsPerMetre *= 2.0;
    }
    return static_cast<float>(sum / norm);
}

}  // namespace cg::algo
