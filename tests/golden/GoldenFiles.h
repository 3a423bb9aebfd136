#pragma once
/// Statistics of the files a run wrote: how many per directory and extension, and what each
/// holds as read back (PNG means, VDB grids, PLY vertex counts, PFM means), never the bytes:
/// VDB files carry fresh UUIDs and compressors may change.

#include <filesystem>

#include "golden/GoldenStats.h"

namespace cg::golden {

/// "files/<dir>/*.<ext>" counts and "files/<dir>/<name>/<stat>" per file read back, for
/// everything under `outDir`.
Stats fileStats(const std::filesystem::path& outDir);

}  // namespace cg::golden
