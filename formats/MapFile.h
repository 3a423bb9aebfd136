#pragma once
/// A painted map read back into a Map2D's values: a greyscale or RGB PNG of 8 or 16 bits, a
/// greyscale PFM or an OpenEXR image, told apart by their first bytes, never by the name.
/// The orientation is WriteMap's: the image's bottom row is the map's row iy = 0 (+y up, +x
/// right, as a paint program shows it). A PNG's samples become q / 255 or q / 65535; an RGB
/// image (PNG or EXR) its Rec. 709 luminance of the stored values (what the painter saw,
/// not linearised); an EXR's "Y" channel is taken as it is. Sizes are checked against
/// `maxPixels` before any pixel is read.

#include <cstdint>
#include <filesystem>

#include "formats/MapImage.h"

namespace cg::formats {

/// A map larger than this many pixels on a side is refused (PNG's own limit is checked
/// before its pixels are read).
constexpr std::uint32_t kMaxMapSide = 16384;

/// Reads `path` as above. Throws FormatError naming the file: not a regular readable file,
/// not one of the formats, more than `maxPixels` pixels or kMaxMapSide on a side, a PNG
/// with alpha or a palette, a colour PFM, a damaged file, a value that is not finite.
MapImage readMapFile(const std::filesystem::path& path, std::uint64_t maxPixels);

}  // namespace cg::formats
