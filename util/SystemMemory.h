#pragma once
/// How much memory this machine can give us now, to refuse work that cannot fit before it
/// starts (and swaps, or is killed) rather than after.

#include <cstdint>

namespace cg::util {

/// Bytes the kernel says can be allocated without swapping (MemAvailable); the physical
/// memory when that is unknown; 0 when even that is unknown.
std::uint64_t availableMemoryBytes();

/// The machine's physical memory in bytes; 0 when unknown.
std::uint64_t physicalMemoryBytes();

/// The most one node may allocate for one value: a quarter of the physical memory (a run
/// holds several nodes' values at once), at most 16 GiB; 16 GiB when the memory is unknown.
/// Fixed for a machine, so that whether a graph is valid does not change from run to run.
std::uint64_t nodeAllocationLimitBytes();

}  // namespace cg::util
