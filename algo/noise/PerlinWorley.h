#pragma once
/// Perlin-Worley noise for cloud detail, the billowy noise production cloud tools erode cloud
/// edges with (Schneider, "The real-time volumetric cloudscapes of Horizon Zero Dawn", 2015):
/// Worley cells give round billows, Perlin noise breaks their regularity.
///
/// One cycle of the noise is precomputed once per process into a tileable 64^3 texture and
/// sampled trilinearly, so an evaluation costs a few cache-resident loads per octave instead
/// of 27 Worley cells. The texture is a pure function of fixed seeds: same value on every
/// machine and for any thread count.

namespace cg::algo {

/// Texels per noise cycle (one Worley cell, one Perlin lattice cell) in the texture.
inline constexpr int kPerlinWorleyTexelsPerCycle = 16;
/// Texels per texture edge: 4 cycles before it repeats.
inline constexpr int kPerlinWorleyTextureSize = 64;

/// The texture's value at texel coordinates (u, v, w), trilinear between texel centres and
/// wrapping: in [0, 1], high inside a billow and low in the creases between billows.
/// Texel t holds the noise at t / kPerlinWorleyTexelsPerCycle cycles. Value (ours):
/// 0.7 (0.75 W(c) + 0.25 W(2c)) + 0.3 (0.5 + 0.5 P(c)), W = 1 - min(F1, 1) the inverted
/// Worley distance to the nearest feature point (one a cell) and P gradient noise.
float perlinWorleyTexel(float u, float v, float w);

/// An upper bound of perlinWorleyTexel and perlinWorleyFbm: the texture's largest texel plus
/// a margin for the float rounding of the interpolation, so a caller can tell where no
/// value of the noise could change its result without evaluating it.
float perlinWorleyUpperBound();

/// Fractal sum of the texture: sum over octaves o of 0.5^o T(2^o frequency x + shift_o),
/// divided by the sum of the weights, so the result stays in [0, 1]. x is in metres and
/// frequency in cycles per metre; shift_o (fixed, ours) decorrelates the octaves' tiles.
/// octaves >= 1.
float perlinWorleyFbm(const double x[3], double frequency, int octaves);

}  // namespace cg::algo
