#pragma once
/// Counter-based random numbers: a value is a pure function of (seed, stream, index), so
/// results never depend on thread count or evaluation order.

#include <cstdint>

namespace cg::algo {

/// SplitMix64 finaliser: a bijective mix with good avalanche.
inline std::uint64_t mix64(std::uint64_t x)
{
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

/// 64 random bits for the counter (seed, stream, index).
inline std::uint64_t counterBits(std::uint64_t seed, std::uint64_t stream, std::uint64_t index)
{
    return mix64(mix64(mix64(seed) ^ stream) ^ index);
}

/// Uniform double in [0, 1) with 53 random bits.
inline double counterUniform(std::uint64_t seed, std::uint64_t stream, std::uint64_t index)
{
    return static_cast<double>(counterBits(seed, stream, index) >> 11) * 0x1.0p-53;
}

}  // namespace cg::algo
