#include "formats/Sounding.h"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <system_error>

#include "formats/FormatError.h"
#include "util/InputFile.h"

namespace cg::formats {

namespace {

constexpr double kMissing = std::numeric_limits<double>::quiet_NaN();
constexpr double kMetresPerSecondPerKnot = 1852.0 / 3600.0;
/// Wyoming's columns are 7 characters wide, each name right-aligned in its column.
constexpr std::size_t kWyomingColumnWidth = 7;
constexpr std::size_t kWyomingColumns = 11;

std::string_view trim(std::string_view s)
{
    const auto first = s.find_first_not_of(" \t");
    if (first == std::string_view::npos) return {};
    return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

std::vector<std::string_view> split(std::string_view s, char separator)
{
    std::vector<std::string_view> fields;
    for (std::size_t at = 0;;) {
        const auto end = s.find(separator, at);
        fields.push_back(trim(s.substr(at, end == std::string_view::npos ? end : end - at)));
        if (end == std::string_view::npos) return fields;
        at = end + 1;
    }
}

std::vector<std::string_view> tokens(std::string_view s)
{
    std::vector<std::string_view> out;
    std::size_t at = 0;
    while ((at = s.find_first_not_of(" \t", at)) != std::string_view::npos) {
        const auto end = s.find_first_of(" \t", at);
        out.push_back(s.substr(at, end == std::string_view::npos ? end : end - at));
        at = end;
    }
    return out;
}

/// A value as a person would write it: 400, 12.5, -56.3.
std::string shown(double v)
{
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

/// Parses the whole of `s` as a finite number into `v`; false for anything else.
bool parseNumber(std::string_view s, double& v)
{
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    return ec == std::errc() && end == s.data() + s.size() && std::isfinite(v);
}

bool isNumber(std::string_view s)
{
    double v = 0.0;
    return parseNumber(s, v);
}

/// The text's lines, numbered from 1, without their line ends ("\n" or "\r\n").
class Lines {
public:
    explicit Lines(std::string_view text) : mText(text) {}
    bool next(std::string_view& line)
    {
        if (mAt >= mText.size()) return false;
        auto end = mText.find('\n', mAt);
        if (end == std::string_view::npos) end = mText.size();
        line = mText.substr(mAt, end - mAt);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        mAt = end + 1;
        ++mNumber;
        return true;
    }
    std::size_t number() const { return mNumber; }

private:
    std::string_view mText;
    std::size_t mAt = 0;
    std::size_t mNumber = 0;
};

/// Builds the levels, checking each as it comes, so that an error names its line and a file
/// of absurdly many levels is refused before they are all stored.
class LevelChecker {
public:
    explicit LevelChecker(const std::string& name) : mName(name) {}

    [[noreturn]] void fail(std::size_t line, const std::string& why) const
    {
        throw FormatError(mName, "line " + std::to_string(line) + ": " + why);
    }

    /// A field's value: NaN when blank; a finite number, else an error naming the column.
    double number(std::string_view field, std::size_t line, const char* column) const
    {
        field = trim(field);
        if (field.empty()) return kMissing;
        double v = 0.0;
        if (!parseNumber(field, v))
            fail(line, std::string(column) + ": '" + std::string(field) + "' is not a number");
        return v;
    }

    void add(const SoundingLevel& l, std::size_t line)
    {
        if (mLevels.size() == kMaxSoundingLevels)
            fail(line, "more than " + std::to_string(kMaxSoundingLevels) + " levels");
        check(l, line);
        mLevels.push_back(l);
    }

    std::vector<SoundingLevel> finish(std::size_t lastLine) &&
    {
        if (mLevels.size() < 2)
            fail(lastLine,
                 "a sounding needs at least two levels with a height and a "
                 "temperature; found " +
                     std::to_string(mLevels.size()));
        return std::move(mLevels);
    }

private:
    void range(double v, double lo, double hi, std::size_t line, const char* what,
               const char* units) const
    {
        if (std::isnan(v) || (v >= lo && v <= hi)) return;
        char text[160];
        std::snprintf(text, sizeof text, "%s %g %s is outside %g .. %g", what, v, units, lo, hi);
        fail(line, text);
    }

    void check(const SoundingLevel& l, std::size_t line)
    {
        range(l.heightM, -1000.0, 100000.0, line, "height", "m");
        range(l.temperatureC, -150.0, 80.0, line, "temperature", "C");
        range(l.dewpointC, -150.0, 80.0, line, "dew point", "C");
        range(l.pressureHPa, 0.001, 1100.0, line, "pressure", "hPa");
        range(l.windFromDeg, 0.0, 360.0, line, "wind direction", "degrees");
        range(l.windSpeedMs, 0.0, 200.0, line, "wind speed", "m/s");
        if (mLevels.empty() && std::isnan(l.dewpointC))
            fail(line, "the first level is the ground and needs a dew point");
        if (l.dewpointC > l.temperatureC + 0.5)  // rounding in published soundings
            fail(line, "dew point " + shown(l.dewpointC) + " C is above the temperature " +
                           shown(l.temperatureC) + " C");
        if (!mLevels.empty() && !(l.heightM > mLevels.back().heightM))
            fail(line, "heights must increase: " + shown(l.heightM) + " m after " +
                           shown(mLevels.back().heightM) + " m");
        if (!std::isnan(l.pressureHPa)) {
            if (!std::isnan(mLastPressure) && !(l.pressureHPa < mLastPressure))
                fail(line, "pressure must fall with height: " + shown(l.pressureHPa) +
                               " hPa after " + shown(mLastPressure) + " hPa");
            mLastPressure = l.pressureHPa;
        }
    }

    const std::string& mName;
    std::vector<SoundingLevel> mLevels;
    double mLastPressure = kMissing;
};

/// The University of Wyoming text list; `header` is the line that names the columns.
std::vector<SoundingLevel> parseWyoming(Lines& lines, std::string_view header,
                                        const std::string& name)
{
    LevelChecker checker(name);
    static constexpr std::array<const char*, kWyomingColumns> kNames = {
        "PRES", "HGHT", "TEMP", "DWPT", "RELH", "MIXR", "DRCT", "SKNT", "THTA", "THTE", "THTV"};
    // Where each column ends: its name is right-aligned in a 7-character field.
    std::array<std::size_t, kWyomingColumns> ends{};
    std::array<std::size_t, kWyomingColumns> order{};  // column index -> token index
    const auto names = tokens(header);
    for (std::size_t c = 0; c < kWyomingColumns; ++c) {
        ends[c] = std::string_view::npos;
        for (std::size_t t = 0; t < names.size(); ++t)
            if (names[t] == kNames[c]) {
                ends[c] = static_cast<std::size_t>(names[t].data() - header.data()) + 4;
                order[c] = t;
            }
    }
    const auto field = [&](std::string_view row, const std::vector<std::string_view>& rowTokens,
                           std::size_t c) -> std::string_view {
        if (ends[c] == std::string_view::npos) return {};
        // Rows with every field filled may have been re-spaced: take them token by token.
        if (rowTokens.size() == names.size()) return rowTokens[order[c]];
        const std::size_t end = ends[c];
        const std::size_t begin = end >= kWyomingColumnWidth ? end - kWyomingColumnWidth : 0;
        if (begin >= row.size()) return {};
        return row.substr(begin, end - begin);
    };

    bool inRows = false;
    std::string_view line;
    while (lines.next(line)) {
        const auto rowTokens = tokens(line);
        bool numeric = !rowTokens.empty();
        for (std::string_view t : rowTokens) numeric = numeric && isNumber(t);
        if (!numeric) {
            if (inRows) break;  // the station indices that follow the rows
            const bool separator = trim(line).find_first_not_of('-') == std::string_view::npos;
            if (separator || line.find("hPa") != std::string_view::npos) continue;  // units
            checker.fail(lines.number(),
                         "expected a row of numbers under the column header, found '" +
                             std::string(trim(line).substr(0, 40)) + "'");
        }
        if (rowTokens.size() > names.size())
            checker.fail(lines.number(), std::to_string(rowTokens.size()) +
                                             " fields, the header "
                                             "names " +
                                             std::to_string(names.size()) + " columns");
        inRows = true;
        const std::size_t n = lines.number();
        SoundingLevel l;
        l.pressureHPa = checker.number(field(line, rowTokens, 0), n, "PRES");
        l.heightM = checker.number(field(line, rowTokens, 1), n, "HGHT");
        l.temperatureC = checker.number(field(line, rowTokens, 2), n, "TEMP");
        l.dewpointC = checker.number(field(line, rowTokens, 3), n, "DWPT");
        l.windFromDeg = checker.number(field(line, rowTokens, 6), n, "DRCT");
        l.windSpeedMs =
            checker.number(field(line, rowTokens, 7), n, "SKNT") * kMetresPerSecondPerKnot;
        // Wyoming lists the standard levels below the ground with a height and nothing else.
        if (std::isnan(l.heightM) || std::isnan(l.temperatureC)) continue;
        checker.add(l, n);
    }
    return std::move(checker).finish(lines.number());
}

/// CSV with a header line; `header` is that line.
std::vector<SoundingLevel> parseCsv(Lines& lines, std::string_view header, const std::string& name)
{
    LevelChecker checker(name);
    static constexpr std::array<const char*, 6> kNames = {
        "height_m", "temperature_C", "dewpoint_C", "pressure_hPa", "wind_dir_deg", "wind_speed_ms"};
    const auto names = split(header, ',');
    std::array<std::size_t, kNames.size()> column{};
    for (std::size_t c = 0; c < kNames.size(); ++c) {
        column[c] = std::string_view::npos;
        for (std::size_t f = 0; f < names.size(); ++f)
            if (names[f] == kNames[c]) column[c] = f;
        if (c < 3 && column[c] == std::string_view::npos)
            checker.fail(lines.number(), std::string("the header has no column '") + kNames[c] +
                                             "' (it needs height_m,temperature_C,dewpoint_C)");
    }
    std::string_view line;
    while (lines.next(line)) {
        if (trim(line).empty() || trim(line).front() == '#') continue;
        const auto fields = split(line, ',');
        const std::size_t n = lines.number();
        if (fields.size() != names.size())
            checker.fail(n, std::to_string(fields.size()) + " fields, the header names " +
                                std::to_string(names.size()));
        const auto value = [&](std::size_t c) {
            return column[c] == std::string_view::npos
                       ? kMissing
                       : checker.number(fields[column[c]], n, kNames[c]);
        };
        SoundingLevel l;
        l.heightM = value(0);
        l.temperatureC = value(1);
        l.dewpointC = value(2);
        l.pressureHPa = value(3);
        l.windFromDeg = value(4);
        l.windSpeedMs = value(5);
        if (std::isnan(l.heightM) || std::isnan(l.temperatureC))
            checker.fail(n, "a level needs a height and a temperature");
        checker.add(l, n);
    }
    return std::move(checker).finish(lines.number());
}

bool namesWyomingColumns(std::string_view line)
{
    bool pres = false, hght = false, temp = false, dwpt = false;
    for (std::string_view t : tokens(line)) {
        pres = pres || t == "PRES";
        hght = hght || t == "HGHT";
        temp = temp || t == "TEMP";
        dwpt = dwpt || t == "DWPT";
    }
    return pres && hght && temp && dwpt;
}

}  // namespace

Sounding parseSounding(std::string_view text, const std::string& name)
{
    for (std::size_t i = 0; i < text.size(); ++i) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c < 0x20 && c != '\n' && c != '\r' && c != '\t') {
            char byte[8];
            std::snprintf(byte, sizeof byte, "0x%02x", c);
            throw FormatError(name, "not a text file: byte " + std::to_string(i) + " is " + byte);
        }
    }
    Lines lines(text);
    std::string_view line;
    while (lines.next(line)) {
        const std::string_view t = trim(line);
        if (t.empty() || t.front() == '#') continue;
        Sounding s;
        if (t.find("height_m") != std::string_view::npos && t.find(',') != std::string_view::npos) {
            s.format = SoundingFormat::Csv;
            s.levels = parseCsv(lines, t, name);
            return s;
        }
        if (namesWyomingColumns(t)) {
            s.format = SoundingFormat::Wyoming;
            s.levels = parseWyoming(lines, line, name);
            return s;
        }
        if (lines.number() > 100) break;  // Wyoming's header is a few lines
    }
    throw FormatError(name,
                      "neither a University of Wyoming text sounding (no PRES HGHT TEMP "
                      "DWPT column header) nor a CSV whose header names "
                      "height_m,temperature_C,dewpoint_C");
}

Sounding readSounding(const std::filesystem::path& path)
{
    if (const std::string problem = util::inputFileProblem(path, kMaxSoundingBytes);
        !problem.empty())
        throw FormatError(path.string(), "cannot read the sounding: it " + problem);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw FormatError(path.string(), "cannot open the sounding");
    // One byte more than its checked size, so a file that grew since is seen, not read whole.
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) throw FormatError(path.string(), "cannot read the sounding: " + ec.message());
    std::string text(static_cast<std::size_t>(size) + 1, '\0');
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    if (in.bad()) throw FormatError(path.string(), "cannot read the sounding");
    text.resize(static_cast<std::size_t>(in.gcount()));
    if (text.size() > size)
        throw FormatError(path.string(), "cannot read the sounding: it changed while read");
    return parseSounding(text, path.string());
}

}  // namespace cg::formats
