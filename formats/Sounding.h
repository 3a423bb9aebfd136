#pragma once
/// Upper-air soundings: a temperature, dew-point and wind profile by height, read from the two
/// text formats users have (detected by content, never by the file name):
///
///  - the University of Wyoming text list (weather.uwyo.edu, "Text: List"): header lines, a
///    column header `PRES HGHT TEMP DWPT RELH MIXR DRCT SKNT THTA THTE THTV` over a units
///    line, then fixed-width rows of 7 characters a column (hPa, m, C, C, %, g/kg, degrees,
///    knots, K, K, K). A blank field is a missing value. Rows without a height or a
///    temperature (levels below the ground, which the list starts with) are skipped; reading
///    stops at the first line after the rows that is not a row (Wyoming's station indices).
///  - CSV: a header naming at least `height_m,temperature_C,dewpoint_C`, optionally
///    `pressure_hPa,wind_dir_deg,wind_speed_ms`, in any order (other columns are ignored),
///    then one level a line. Empty fields are missing values; lines starting with '#' and
///    blank lines are skipped.
///
/// Heights are above mean sea level and must increase; the first level is the ground and must
/// have a dew point. Every error names the file and the line.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace cg::formats {

/// One level; NaN marks a missing value (never height or temperature).
struct SoundingLevel {
    double heightM = 0.0;  ///< above mean sea level
    double temperatureC = 0.0;
    double dewpointC = 0.0;    ///< <= temperatureC (+ 0.5 C of rounding)
    double pressureHPa = 0.0;  ///< decreasing with height where given
    double windFromDeg = 0.0;  ///< the direction the wind blows from, clockwise from north
    double windSpeedMs = 0.0;  ///< m/s (Wyoming's knots converted)
};

enum class SoundingFormat { Wyoming, Csv };

struct Sounding {
    SoundingFormat format = SoundingFormat::Csv;
    std::vector<SoundingLevel> levels;  ///< by increasing height; levels[0] is the ground
};

/// A sounding file larger than this is not a sounding (a dense radiosonde ascent at 1 s
/// resolution is about 1 MB).
constexpr std::uint64_t kMaxSoundingBytes = 32ull << 20;
/// Nor is one with more levels than this.
constexpr std::size_t kMaxSoundingLevels = 100000;

/// Reads and checks a sounding file: first that it is a regular file of at most
/// kMaxSoundingBytes, then its text. Throws FormatError naming the file (and the line).
Sounding readSounding(const std::filesystem::path& path);

/// Parses sounding text; `name` stands for the file in messages. Throws FormatError.
Sounding parseSounding(std::string_view text, const std::string& name);

}  // namespace cg::formats
