// The primitive-set file format (formats/PrimitiveFile.h).

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "formats/FormatError.h"
#include "formats/PrimitiveFile.h"
#include "support/TestUtil.h"

namespace cg::formats {

namespace {
void sample(std::vector<std::uint32_t>& counts, std::vector<float>& pos)
{
    counts = {0, 2, 3, 3};
    for (std::uint32_t n : counts)
        for (std::uint32_t i = 0; i < 3 * n; ++i)
            pos.push_back(0.25f * static_cast<float>(i) - 1.0f + n);
}
}  // namespace

TEST(PrimitiveFile, RoundTripIsExactWithRandomAccess)
{
    test::TempDir dir;
    std::vector<std::uint32_t> counts;
    std::vector<float> pos;
    sample(counts, pos);
    writePrimitiveFile(dir / "p.cgp", 0.5, counts, pos);
    PrimitiveFileReader r(dir / "p.cgp");
    EXPECT_EQ(r.frames(), 4);
    EXPECT_EQ(r.frameTime(), 0.5);
    EXPECT_EQ(r.counts(), counts);
    EXPECT_EQ(r.readAll(), pos);
    const std::vector<float> f2 = r.readFrame(2);
    EXPECT_EQ(f2, std::vector<float>(pos.begin() + 6, pos.begin() + 15));
}

TEST(PrimitiveFile, TruncatedAlteredAndForeignFilesAreRefused)
{
    test::TempDir dir;
    std::vector<std::uint32_t> counts;
    std::vector<float> pos;
    sample(counts, pos);
    writePrimitiveFile(dir / "p.cgp", 0.5, counts, pos);
    const std::string bytes = test::readFile(dir / "p.cgp");
    auto refused = [&](const std::string& content, const std::string& what) {
        test::writeFile(dir / "bad.cgp", content);
        try {
            PrimitiveFileReader r(dir / "bad.cgp");
            r.readAll();
        } catch (const formats::FormatError& e) {
            EXPECT_NE(e.where().find("bad.cgp:"), std::string::npos) << what << ": " << e.what();
            return;
        }
        ADD_FAILURE() << what << " was accepted";
    };
    for (std::size_t cut :
         {std::size_t{0}, std::size_t{10}, std::size_t{63}, std::size_t{70}, bytes.size() - 1})
        refused(bytes.substr(0, cut), "truncated at " + std::to_string(cut));
    for (std::size_t at = 0; at < bytes.size(); ++at) {
        std::string flipped = bytes;
        flipped[at] = static_cast<char>(flipped[at] ^ 0x10);
        refused(flipped, "bit flip at " + std::to_string(at));
    }
    refused("ply\nformat ascii 1.0\n" + std::string(100, 'x'), "foreign");
    refused(bytes + "x", "trailing bytes");
    // A huge frame count in a tiny file is refused before anything is allocated.
    std::string huge = bytes;
    huge[12] = huge[13] = huge[14] = static_cast<char>(0xff);
    refused(huge, "huge frame count");
}

}  // namespace cg::formats
