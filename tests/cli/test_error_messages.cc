// Error messages print whole: user input quoted in them (a node id, a file name) may hold
// any character, and a NUL must not cut the message short where it is printed.

#include <gtest/gtest.h>

#include <string>

#include "core/JsonParse.h"
#include "support/TestUtil.h"

namespace cg {
namespace {

TEST(ErrorMessages, ControlCharactersAreEscapedAndTheRestKept)
{
    EXPECT_EQ(printableText(std::string("a\0b\x01"
                                        "c\nd",
                                        7)),
              "a\\x00b\\x01c\nd");
    EXPECT_EQ(printableText("caf\xc3\xa9\t\x7f"), "caf\xc3\xa9\t\\x7f");  // UTF-8 kept
}

TEST(ErrorMessages, ANodeIdWithANulIsNamedWholeByTheCli)
{
    test::TempDir dir;
    test::writeFile(dir / "g.json",
                    R"({"cloudgraph": 1, "nodes": {"a\u0000evil": {"type": "Oscillator"}}})");
    const test::CliResult r = test::runCli({"validate", (dir / "g.json").string()});
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.errors.find("a\\x00evil"), std::string::npos) << r.errors;
    EXPECT_NE(r.errors.find("ids match"), std::string::npos) << r.errors;
}

}  // namespace
}  // namespace cg
