#pragma once
/// How much memory this machine can give us now, to refuse work that cannot fit before it
/// starts (and swaps, or is killed) rather than after.

#include <cstdint>

namespace cg::util {

/// Bytes the kernel says can be allocated without swapping (MemAvailable); the physical
/// memory when that is unknown; 0 when even that is unknown.
std::uint64_t availableMemoryBytes();

}  // namespace cg::util
