#pragma once
/// Bounding a disk cache's size. A cache grows with every frame and every parameter tried
/// (the default run leaves about 3 GB); pruning removes whole entries, least recently used
/// first, so a bounded cache keeps what the current work reads and recooks the rest.
///
/// "Recently used" is the entry file's modification time: DiskCache::store writes it and
/// DiskCache::load refreshes it. Only entries (objects/) are counted and removed; records
/// (kilobytes, they tell writers whether their files are fresh) and tmp/ are left alone.
/// Removing an entry another process is reading is safe: it keeps its open file, and a
/// later load is a miss that recooks.

#include <cstdint>
#include <filesystem>
#include <string_view>

namespace cg {

struct CacheUsage {
    std::uint64_t bytes = 0;
    std::uint64_t entries = 0;
};

/// What the entries under `root`/objects take (a missing cache takes nothing).
CacheUsage cacheUsage(const std::filesystem::path& root);

/// Removes entries, the oldest modification time first (ties by path, so the choice does
/// not depend on directory order), until the rest take at most `maxBytes`. Returns what was
/// removed. Entries that vanish meanwhile (another process pruning) are skipped.
CacheUsage pruneCache(const std::filesystem::path& root, std::uint64_t maxBytes);

/// Bytes from "800000", "500M", "2G", "1.5T" (powers of 1024; K, M, G, T, an optional
/// trailing "B" or "iB"). Throws InputError naming `where` for anything else.
std::uint64_t parseByteSize(std::string_view text, std::string_view where);

}  // namespace cg
