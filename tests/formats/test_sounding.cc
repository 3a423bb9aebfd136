// The sounding reader (formats/Sounding.h): both formats, blank fields, and every refusal named
// by file and line before anything large is read.

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "formats/FormatError.h"
#include "formats/Sounding.h"
#include "support/TestUtil.h"

namespace cg::formats {

namespace {

namespace fs = std::filesystem;

const fs::path kSoundings = fs::path(CLOUDGRAPH_SOURCE_DIR) / "tests" / "data" / "soundings";
constexpr double kMetresPerSecondPerKnot = 1852.0 / 3600.0;

/// The message of the FormatError that parsing `text` throws; empty if it does not throw.
std::string refusal(const std::string& text)
{
    try {
        parseSounding(text, "s.csv");
    } catch (const FormatError& e) {
        EXPECT_EQ(e.where(), "s.csv");
        return e.message();
    }
    return "";
}

const std::string kCsvHeader = "height_m,temperature_C,dewpoint_C\n";

}  // namespace

TEST(Sounding, WyomingTextListParsesWithBlankFieldsAndSkipsLevelsBelowTheGround)
{
    const Sounding s = readSounding(kSoundings / "wyoming_sample.txt");
    EXPECT_EQ(s.format, SoundingFormat::Wyoming);
    ASSERT_EQ(s.levels.size(), 11u);  // the 1000 hPa row lies below the ground: no temperature
    const SoundingLevel& ground = s.levels.front();
    EXPECT_EQ(ground.heightM, 180.0);
    EXPECT_EQ(ground.temperatureC, 24.0);
    EXPECT_EQ(ground.dewpointC, 16.0);
    EXPECT_EQ(ground.pressureHPa, 990.0);
    EXPECT_EQ(ground.windFromDeg, 200.0);
    EXPECT_DOUBLE_EQ(ground.windSpeedMs, 6 * kMetresPerSecondPerKnot);
    const SoundingLevel& top = s.levels.back();
    EXPECT_EQ(top.heightM, 11950.0);
    EXPECT_EQ(top.temperatureC, -56.3);
    EXPECT_TRUE(std::isnan(top.dewpointC));  // a blank DWPT field
    EXPECT_DOUBLE_EQ(top.windSpeedMs, 45 * kMetresPerSecondPerKnot);
}

TEST(Sounding, CsvInAnyColumnOrderGivesTheSameLevelsAsTheWyomingList)
{
    const Sounding wyoming = readSounding(kSoundings / "wyoming_sample.txt");
    const Sounding csv = readSounding(kSoundings / "csv_sample.csv");
    EXPECT_EQ(csv.format, SoundingFormat::Csv);
    ASSERT_EQ(csv.levels.size(), wyoming.levels.size());
    for (std::size_t i = 0; i < csv.levels.size(); ++i) {
        SCOPED_TRACE("level " + std::to_string(i));
        const SoundingLevel& a = csv.levels[i];
        const SoundingLevel& b = wyoming.levels[i];
        EXPECT_EQ(a.heightM, b.heightM);
        EXPECT_EQ(a.temperatureC, b.temperatureC);
        if (std::isnan(b.dewpointC)) {
            EXPECT_TRUE(std::isnan(a.dewpointC));
        } else {
            EXPECT_EQ(a.dewpointC, b.dewpointC);
        }
        EXPECT_EQ(a.pressureHPa, b.pressureHPa);
        EXPECT_EQ(a.windFromDeg, b.windFromDeg);
        EXPECT_NEAR(a.windSpeedMs, b.windSpeedMs, 1e-6);
    }
}

TEST(Sounding, CsvWithOnlyTheRequiredColumnsHasNoPressureOrWind)
{
    const Sounding s = parseSounding(kCsvHeader + "0,20,12\n1000,14,\r\n", "s.csv");
    ASSERT_EQ(s.levels.size(), 2u);
    EXPECT_EQ(s.levels[1].temperatureC, 14.0);
    EXPECT_TRUE(std::isnan(s.levels[1].dewpointC));
    EXPECT_TRUE(std::isnan(s.levels[0].pressureHPa));
    EXPECT_TRUE(std::isnan(s.levels[0].windSpeedMs));
}

TEST(Sounding, WyomingRowsWithEveryFieldAreReadTokenByTokenWhateverTheSpacing)
{
    const std::string header =
        "   PRES   HGHT   TEMP   DWPT   RELH   MIXR   DRCT   SKNT   THTA   THTE   THTV\n";
    const Sounding s =
        parseSounding(header +
                          "990 180 24 16 61 11.6 200 6 297.9 331.8 300\n"
                          "950\t530\t20.4\t14.8\t70\t11.16\t210\t8\t297.8\t330.4\t299.8\n",
                      "w.txt");
    ASSERT_EQ(s.levels.size(), 2u);
    EXPECT_EQ(s.levels[1].heightM, 530.0);
    EXPECT_EQ(s.levels[1].dewpointC, 14.8);
    EXPECT_EQ(s.levels[1].windFromDeg, 210.0);
}

TEST(Sounding, MalformedTextIsRefusedNamingTheLine)
{
    // Each refusal names the line at fault (line 1 is the header).
    EXPECT_EQ(refusal(kCsvHeader + "0,20,12\n500,15,10\n400,16,10\n"),
              "line 4: heights must increase: 400 m after 500 m");
    EXPECT_EQ(refusal(kCsvHeader + "0,20,12\n500,warm,10\n"),
              "line 3: temperature_C: 'warm' is not a number");
    EXPECT_EQ(refusal(kCsvHeader + "0,20,12\n500,1e999,10\n"),
              "line 3: temperature_C: '1e999' is not a number");
    EXPECT_EQ(refusal("height_m,temperature_C\n0,20\n"),
              "line 1: the header has no column 'dewpoint_C' (it needs "
              "height_m,temperature_C,dewpoint_C)");
    EXPECT_EQ(refusal(kCsvHeader + "0,20,12\n500,15\n"), "line 3: 2 fields, the header names 3");
    EXPECT_EQ(refusal(kCsvHeader + "0,20,\n500,15,10\n"),
              "line 2: the first level is the ground and needs a dew point");
    EXPECT_EQ(refusal(kCsvHeader + "0,20,22\n500,15,10\n"),
              "line 2: dew point 22 C is above the temperature 20 C");
    EXPECT_EQ(refusal(kCsvHeader + "0,20,12\n500,215,10\n"),
              "line 3: temperature 215 C is outside -150 .. 80");
    EXPECT_EQ(refusal("height_m,temperature_C,dewpoint_C,pressure_hPa\n0,20,12,1000\n500,15,10,"
                      "1001\n"),
              "line 3: pressure must fall with height: 1001 hPa after 1000 hPa");
    EXPECT_EQ(refusal(kCsvHeader + "0,20,12\n"),
              "line 2: a sounding needs at least two levels with a height and a temperature; "
              "found 1");
    EXPECT_EQ(refusal("PRES HGHT TEMP DWPT\n hello\n"),
              "line 2: expected a row of numbers under the column header, found 'hello'");
    EXPECT_EQ(refusal("temperature,height\n20,0\n"),
              "neither a University of Wyoming text sounding (no PRES HGHT TEMP DWPT column "
              "header) nor a CSV whose header names height_m,temperature_C,dewpoint_C");
    EXPECT_EQ(refusal(kCsvHeader + std::string("0,20,12\n\x7f\x45LF\0\x01", 14)),
              "not a text file: byte 46 is 0x00");
}

TEST(Sounding, TooManyLevelsAreRefusedAtTheFirstOneOver)
{
    std::string text = kCsvHeader;
    for (std::size_t i = 0; i <= kMaxSoundingLevels; ++i) text += std::to_string(i) + ",10,5\n";
    EXPECT_EQ(refusal(text), "line " + std::to_string(kMaxSoundingLevels + 2) + ": more than " +
                                 std::to_string(kMaxSoundingLevels) + " levels");
}

TEST(Sounding, FilesAreCheckedBeforeTheyAreRead)
{
    test::TempDir dir;
    // A billion lines would take 1 GB: refused by its size, without reading a byte of it.
    const fs::path huge = dir / "huge.csv";
    test::writeFile(huge, kCsvHeader);
    ASSERT_EQ(::truncate(huge.c_str(), 1ll << 30), 0);
    const auto message = [](const fs::path& p) {
        try {
            readSounding(p);
        } catch (const FormatError& e) {
            EXPECT_EQ(e.where(), p.string());
            return e.message();
        }
        return std::string();
    };
    EXPECT_EQ(message(huge),
              "cannot read the sounding: it is 1073741824 bytes, over the limit of " +
                  std::to_string(kMaxSoundingBytes) + " bytes");
    EXPECT_EQ(message(dir.path()), "cannot read the sounding: it is a directory, not a file");
    const fs::path fifo = dir / "fifo";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_EQ(message(fifo),
              "cannot read the sounding: it is not a regular file (a device, FIFO or socket)");
    EXPECT_NE(message(dir / "missing.csv"), "");
}

}  // namespace cg::formats
