#pragma once
/// Transparent huge pages for large arrays: first touching a fresh array then faults once
/// per 2 MiB instead of once per 4 KiB. Advice only, Linux only; elsewhere nothing happens.

#include <cstddef>

namespace cg::util {

/// Arrays from this size on are worth advising.
inline constexpr std::size_t kHugePageAdviceBytes = std::size_t{8} << 20;

/// Advises the whole pages inside [p, p + bytes) onto huge pages (madvise MADV_HUGEPAGE).
/// Failure is ignored: it is a hint.
void adviseHugePages(void* p, std::size_t bytes);

}  // namespace cg::util
