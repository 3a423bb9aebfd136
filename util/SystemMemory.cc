#include "util/SystemMemory.h"

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <string>

namespace cg::util {

std::uint64_t availableMemoryBytes()
{
    // Linux: MemAvailable counts reclaimable page cache, unlike _SC_AVPHYS_PAGES.
    std::ifstream meminfo("/proc/meminfo");
    std::string key;
    std::uint64_t kib = 0;
    while (meminfo >> key >> kib) {
        if (key == "MemAvailable:") return kib * 1024;
        meminfo.ignore(64, '\n');
    }
    return physicalMemoryBytes();
}

std::uint64_t physicalMemoryBytes()
{
#if defined(_SC_PHYS_PAGES)
    const long pages = ::sysconf(_SC_PHYS_PAGES);
    const long pageSize = ::sysconf(_SC_PAGESIZE);
    if (pages > 0 && pageSize > 0)
        return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(pageSize);
#endif
    return 0;
}

std::uint64_t nodeAllocationLimitBytes()
{
    constexpr std::uint64_t kMostForOneNode = 16ull << 30;
    const std::uint64_t physical = physicalMemoryBytes();
    return physical == 0 ? kMostForOneNode : std::min(kMostForOneNode, physical / 4);
}

}  // namespace cg::util
