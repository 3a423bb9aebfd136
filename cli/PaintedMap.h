#pragma once
/// The maps an artist paints on serve's preview of a map, written as the 8-bit greyscale
/// PNG a ReadMap reads: pixels top row first, the preview's orientation, which is
/// ReadMap's (the bottom row is the map's iy = 0). A painting never replaces a file: each
/// is a new one, <out>/paintings/<node>.<k>.png with the first k not taken.

#include <filesystem>
#include <string>

namespace cg::cli {

/// The most pixels a painting may have: its hex text fits serve's 1 MiB request body.
constexpr long kMaxPaintedPixels = 500000;

/// Writes `width` x `height` grey samples given as `hex` (two hexadecimal digits a pixel,
/// top row first) for the map of node `node` under `outDir`; returns the file's path.
/// Throws InputError naming `what` ("width", "grey", ...) for a size out of range or text
/// that is not that many hex pairs (checked before anything is allocated), and for a file
/// that cannot be written (nothing is left behind).
std::filesystem::path writePaintedMap(const std::filesystem::path& outDir, const std::string& node,
                                      long width, long height, const std::string& hex);

}  // namespace cg::cli
