// cloudgraph info FILE.

#include <gtest/gtest.h>

#include "formats/PrimitiveFile.h"
#include "support/TestUtil.h"

namespace cg {

TEST(InfoCommand, SummarisesAPrimitiveFileAndRefusesADamagedOne)
{
    test::TempDir dir;
    formats::writePrimitiveFile(dir / "p.cgp", 2.0, {1, 2}, {0, 0, 1, 0, 0, 2, 3, 4, 5});
    const auto ok = test::runCli({"info", (dir / "p.cgp").string()});
    EXPECT_EQ(ok.exitCode, 0) << ok.errors;
    EXPECT_NE(ok.output.find("frames:      2"), std::string::npos) << ok.output;
    EXPECT_NE(ok.output.find("N_f(last) = 2"), std::string::npos) << ok.output;
    std::string bytes = test::readFile(dir / "p.cgp");
    bytes[bytes.size() - 12] ^= 1;
    test::writeFile(dir / "bad.cgp", bytes);
    const auto bad = test::runCli({"info", (dir / "bad.cgp").string()});
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_NE(bad.errors.find("bad.cgp:"), std::string::npos) << bad.errors;
}

}  // namespace cg
