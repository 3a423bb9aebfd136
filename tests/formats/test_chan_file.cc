// Nuke .chan camera files (formats/ChanFile.h): text that reads back as the same numbers,
// comments and the optional field of view, and every refusal named by file and line.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "formats/ChanFile.h"
#include "formats/FormatError.h"
#include "support/TestUtil.h"

namespace cg::formats {

namespace {

/// Where the FormatError that parsing `text` throws says the fault is, and its message.
std::pair<std::string, std::string> refusal(const std::string& text)
{
    try {
        parseChan(text, "cam.chan");
    } catch (const FormatError& e) {
        return {e.where(), e.message()};
    }
    return {"", ""};
}

}  // namespace

TEST(ChanFile, WrittenTextReadsBackAsTheSameNumbers)
{
    std::vector<ChanLine> lines(3);
    lines[0] = {-2, {3200.125, 2000.0, 6500.000000001}, {10.5, -0.1, 1e-7}, 45.0};
    lines[1] = {0, {1.0 / 3.0, -2.0 / 7.0, 1e6}, {-89.99, 179.5, 0.0}, 12.345678901234};
    lines[2] = {250, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, 170.0};
    const std::string text = chanText(lines);
    const std::vector<ChanLine> back = parseChan(text, "cam.chan");
    ASSERT_EQ(back.size(), lines.size());
    for (std::size_t i = 0; i < lines.size(); ++i) {
        EXPECT_EQ(back[i].frame, lines[i].frame);
        for (int a = 0; a < 3; ++a) {
            EXPECT_EQ(back[i].translate[a], lines[i].translate[a]);
            EXPECT_EQ(back[i].rotateDegrees[a], lines[i].rotateDegrees[a]);
        }
        EXPECT_EQ(back[i].verticalFovDegrees, lines[i].verticalFovDegrees);
    }
    EXPECT_EQ(chanText(back), text);
    EXPECT_EQ(text.substr(0, 3), "-2 ");
}

TEST(ChanFile, CommentsBlankLinesTabsAndSevenColumnsAreRead)
{
    const std::vector<ChanLine> lines =
        parseChan("# exported by Nuke\n\n1\t0 1 2\t10 20 30\r\n  2 0 1 2 10 20 30 39.5\n", "c");
    ASSERT_EQ(lines.size(), 2u);
    EXPECT_EQ(lines[0].frame, 1);
    EXPECT_EQ(lines[0].translate[2], 2.0);
    EXPECT_EQ(lines[0].rotateDegrees[2], 30.0);
    EXPECT_EQ(lines[0].verticalFovDegrees, 0.0);  // none given
    EXPECT_EQ(lines[1].verticalFovDegrees, 39.5);
    // A line without a field of view is written back without one (the fuzzer found 0).
    EXPECT_EQ(chanText(lines), "1 0 1 2 10 20 30\n2 0 1 2 10 20 30 39.5\n");
    EXPECT_EQ(parseChan(chanText(lines), "again").size(), 2u);
}

TEST(ChanFile, BadLinesAreRefusedNamingTheFileAndTheLine)
{
    EXPECT_EQ(refusal("1 0 0 0 0 0 0 40\n2 0 0 x 0 0 0 40\n").first, "cam.chan:2");
    EXPECT_NE(refusal("1 0 0 x 0 0 0\n").second.find("translate z 'x' is not a number"),
              std::string::npos);
    EXPECT_NE(refusal("1 0 0 0 0 0\n").second.find("7 or 8 numbers"), std::string::npos);
    EXPECT_NE(refusal("1 0 0 0 0 0 0 40 1\n").second.find("not 9"), std::string::npos);
    EXPECT_NE(refusal("1.5 0 0 0 0 0 0\n").second.find("whole number"), std::string::npos);
    EXPECT_NE(refusal("1 0 0 0 0 0 0 180\n").second.find("field of view"), std::string::npos);
    EXPECT_NE(refusal("1 0 0 0 0 0 0 nan\n").second.find("not finite"), std::string::npos);
    EXPECT_NE(refusal("1 0 0 0 1e7 0 0\n").second.find("beyond"), std::string::npos);
    const auto order = refusal("5 0 0 0 0 0 0\n# gap\n5 0 0 0 0 0 0\n");
    EXPECT_EQ(order.first, "cam.chan:3");
    EXPECT_NE(order.second.find("frame 5 does not come after"), std::string::npos);
    EXPECT_EQ(refusal("# nothing\n\n").first, "cam.chan");
    EXPECT_EQ(refusal("").second.find("no camera lines"), 0u);
}

TEST(ChanFile, AFileIsReadAndAMissingOneIsRefusedNamingIt)
{
    const test::TempDir dir;
    const std::filesystem::path file = dir.path() / "shot.chan";
    std::ofstream(file) << "7 1 2 3 4 5 6 30\n";
    const std::vector<ChanLine> lines = readChan(file);
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_EQ(lines[0].frame, 7);
    try {
        readChan(dir.path() / "missing.chan");
        ADD_FAILURE() << "a missing file was read";
    } catch (const FormatError& e) {
        EXPECT_NE(e.where().find("missing.chan"), std::string::npos);
    }
}

}  // namespace cg::formats
