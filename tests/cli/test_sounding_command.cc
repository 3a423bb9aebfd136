// cloudgraph sounding FILE: a sounding's levels and its lifted parcel; bad files exit 2.

#include <gtest/gtest.h>

#include "support/TestUtil.h"

namespace cg {

TEST(SoundingCommand, PrintsTheParcelLevelsOfEitherFormat)
{
    for (const char* name : {"wyoming_sample.txt", "csv_sample.csv"}) {
        SCOPED_TRACE(name);
        const auto r = test::runCli({"sounding", test::dataPath(std::string("soundings/") + name)
                                                     .string()});
        EXPECT_EQ(r.exitCode, 0) << r.errors;
        EXPECT_NE(r.output.find("11 levels from 180 m to 11950 m"), std::string::npos)
            << r.output;
        // 24.0 C over a 16.0 C dew point: 8 C / (9.76 - 1.8) C/km = 1005 m above the ground.
        EXPECT_NE(r.output.find("LCL:     1185 m (1005 m above the ground)"), std::string::npos)
            << r.output;
        EXPECT_NE(r.output.find("CAPE:"), std::string::npos) << r.output;
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

}  // namespace cg
