#pragma once
/// Nuke's `.chan` camera files, which Nuke, Houdini, Maya and Blender's bundled importer read
/// and write: one line a frame, whitespace-separated numbers
///
///     frame  translate.x translate.y translate.z  rotate.x rotate.y rotate.z  [vertical fov]
///
/// translations in scene units, rotations in degrees, the field of view in degrees (optional
/// on reading; a camera without it keeps the one it had). Blank lines and lines starting with
/// '#' are skipped. What the numbers mean (axes, rotation order) is the convention of
/// algo/render/CameraMatrices.h; this file only reads and writes the text. Every error names
/// the file and the line.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace cg::formats {

struct ChanLine {
    std::int64_t frame = 0;
    double translate[3] = {0.0, 0.0, 0.0};
    double rotateDegrees[3] = {0.0, 0.0, 0.0};
    double verticalFovDegrees = 0.0;  ///< 0 where the line has no eighth column
};

/// A .chan file larger than this is not a camera (a 10-hour shot at 24 fps is about 70 MB at
/// most; real files are kilobytes).
constexpr std::uint64_t kMaxChanBytes = 64ull << 20;

/// Parses .chan text; `name` stands for the file in messages. Frames must be whole numbers
/// within +-10^9 and strictly increasing, every value finite, rotations within +-10^6
/// degrees, the field of view (where given) in (0, 180), at least one line. Throws
/// FormatError.
std::vector<ChanLine> parseChan(std::string_view text, const std::string& name);

/// Reads a regular file of at most kMaxChanBytes and parses it. Throws FormatError.
std::vector<ChanLine> readChan(const std::filesystem::path& path);

/// The text of `lines`, each with its field of view where it has one (not 0), every value in
/// the shortest form that reads back as the same double, so parseChan(chanText(lines)) ==
/// lines.
std::string chanText(const std::vector<ChanLine>& lines);

}  // namespace cg::formats
