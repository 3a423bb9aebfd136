#pragma once
/// Greyscale images of a 2D map: PFM (float32, exact) and 16-bit PNG (a preview).
///
/// Maps are row-major with index = iy * nx + ix, and row iy = 0 is the ground's y = 0 edge.
/// Both formats are written so that a viewer shows +y up and +x right: the map's row iy = 0
/// is the bottom row of the image. In PFM, whose rows are stored bottom to top, that is the
/// first row in the file; in PNG, stored top to bottom, it is the last.
///
/// The writers write exactly to `path` (callers pass a temp name from AtomicOutput, so the
/// format is never inferred from the extension). All functions throw std::runtime_error
/// naming the file on I/O failures or malformed input, std::invalid_argument on bad sizes.

#include <string>
#include <vector>

namespace cg::formats {

struct MapImage {
    int nx = 0;
    int ny = 0;
    std::vector<float> values;  ///< row-major, index = iy * nx + ix, iy = 0 at the bottom
};

/// Greyscale PFM: "Pf\n<nx> <ny>\n-1.0\n" then nx * ny little-endian float32, rows from
/// the bottom (iy = 0) up. Values are written unchanged (any range). values.size() must be
/// nx * ny with nx, ny >= 1.
void writePfm(const std::string& path, int nx, int ny, const std::vector<float>& values);

/// Reads a greyscale PFM ("Pf", either byte order, scale magnitude ignored). Refuses colour
/// PFMs, bad headers, non-positive sizes and a data length other than nx * ny * 4 bytes.
MapImage readPfm(const std::string& path);

/// 16-bit greyscale PNG: a value v becomes round(clamp(v, 0, 1) * 65535) (NaN becomes 0).
/// Same orientation as the PFM.
void writePng16(const std::string& path, int nx, int ny, const std::vector<float>& values);

/// Reads a 16-bit greyscale PNG (for tests); samples q become q / 65535.
MapImage readPng16(const std::string& path);

}  // namespace cg::formats
