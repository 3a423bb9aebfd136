#pragma once
/// Integer lattice coordinates (a voxel block, a cell) packed into one 64-bit key for hash
/// maps and sorting: 21 bits per axis, each biased by 2^20, x in the high bits and z in the
/// low, so keys sort x-major with z fastest. Coordinates must lie in [-2^20, 2^20)
/// (coordKeyable); callers check before packing. No engine includes.

#include <array>
#include <cstdint>

namespace cg::algo {

inline constexpr int kCoordKeyBits = 21;
inline constexpr std::int64_t kCoordKeyBias = std::int64_t(1) << (kCoordKeyBits - 1);

/// Whether c fits a key.
inline bool coordKeyable(std::int64_t c) { return c >= -kCoordKeyBias && c < kCoordKeyBias; }

inline std::uint64_t packCoordKey(int x, int y, int z)
{
    return (std::uint64_t(x + kCoordKeyBias) << (2 * kCoordKeyBits)) |
           (std::uint64_t(y + kCoordKeyBias) << kCoordKeyBits) | std::uint64_t(z + kCoordKeyBias);
}

inline std::array<int, 3> unpackCoordKey(std::uint64_t key)
{
    constexpr std::uint64_t mask = (std::uint64_t(1) << kCoordKeyBits) - 1;
    return {static_cast<int>(std::int64_t(key >> (2 * kCoordKeyBits)) - kCoordKeyBias),
            static_cast<int>(std::int64_t((key >> kCoordKeyBits) & mask) - kCoordKeyBias),
            static_cast<int>(std::int64_t(key & mask) - kCoordKeyBias)};
}

}  // namespace cg::algo
