// cloudgraph sounding FILE: a sounding's levels and its lifted parcel; bad files exit 2.

#include <gtest/gtest.h>

#include <filesystem>

#include "formats/PngFile.h"
#include "support/TestUtil.h"

namespace cg {

TEST(SoundingCommand, PrintsTheParcelLevelsOfEitherFormat)
{
    for (const char* name : {"wyoming_sample.txt", "csv_sample.csv"}) {
        SCOPED_TRACE(name);
        const auto r =
            test::runCli({"sounding", test::dataPath(std::string("soundings/") + name).string()});
        EXPECT_EQ(r.exitCode, 0) << r.errors;
        EXPECT_NE(r.output.find("11 levels from 180 m to 11950 m"), std::string::npos) << r.output;
        // 24.0 C over a 16.0 C dew point: 8 C / (9.76 - 1.8) C/km = 1005 m above the ground.
        EXPECT_NE(r.output.find("LCL:     1185 m (1005 m above the ground)"), std::string::npos)
            << r.output;
        EXPECT_NE(r.output.find("CAPE:"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("CCL:"), std::string::npos) << r.output;
    }
}

TEST(SoundingCommand, AMalformedFileExitsTwoNamingTheFileAndLine)
{
    test::TempDir dir;
    test::writeFile(dir / "s.csv", "height_m,temperature_C,dewpoint_C\n0,20,12\n500,warm,10\n");
    const auto r = test::runCli({"sounding", (dir / "s.csv").string()});
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.errors.find("s.csv: line 3: temperature_C: 'warm' is not a number"),
              std::string::npos)
        << r.errors;
    EXPECT_EQ(test::runCli({"sounding"}).exitCode, 2);
}

TEST(SoundingCommand, PlotWritesTheSkewTDiagram)
{
    test::TempDir dir;
    const std::string png = (dir / "skewt.png").string();
    const auto r = test::runCli(
        {"sounding", test::dataPath("soundings/csv_sample.csv").string(), "--plot", png});
    ASSERT_EQ(r.exitCode, 0) << r.errors;
    EXPECT_NE(r.output.find("skew-T:  " + png), std::string::npos) << r.output;
    const formats::Rgb8Image image = formats::readPngRgb8(png);
    EXPECT_EQ(image.width, 640);
    EXPECT_EQ(image.height, 720);
    std::size_t red = 0;
    for (std::size_t i = 0; i < image.rgb.size(); i += 3)
        red += image.rgb[i] == 200 && image.rgb[i + 1] == 30 && image.rgb[i + 2] == 30;
    EXPECT_GT(red, 500u) << "no environment curve";
    std::size_t files = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir.path()))
        files += e.is_regular_file();
    EXPECT_EQ(files, 1u) << "a temporary file was left beside the plot";
}

TEST(SoundingCommand, AGraphWithAMalformedSoundingExitsTwoNamingTheFileLineAndParameter)
{
    test::TempDir dir;
    test::writeFile(dir / "s.csv", "height_m,temperature_C,dewpoint_C\n0,20,12\n500,warm,10\n");
    test::writeFile(dir / "g.json",
                    R"({"cloudgraph": 1, "frames": {"start": 0, "end": 1}, "nodes": {
        "atmosphere": {"type": "Atmosphere", "params": {"profile": "sounding", "soundingFile": "s.csv"}}}})");
    for (const std::string command : {"validate", "run"}) {
        std::vector<std::string> args = {command, (dir / "g.json").string()};
        if (command == "run") args.insert(args.end(), {"--out", (dir / "out").string()});
        const auto r = test::runCli(args);
        EXPECT_EQ(r.exitCode, 2) << command << ": " << r.errors;
        EXPECT_NE(r.errors.find("g.json:/nodes/atmosphere/params/soundingFile"), std::string::npos)
            << r.errors;
        EXPECT_NE(r.errors.find("s.csv: line 3: temperature_C: 'warm' is not a number"),
                  std::string::npos)
            << r.errors;
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "out")) << "a refused run wrote files";
}

}  // namespace cg
