// PFM and 16-bit PNG writing and reading: round trips, orientation, malformed files.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "formats/MapImage.h"
#include "support/TestUtil.h"

namespace cg {

namespace {

std::vector<float> ramp(int nx, int ny)
{
    std::vector<float> v(static_cast<std::size_t>(nx * ny));
    for (int iy = 0; iy < ny; ++iy)
        for (int ix = 0; ix < nx; ++ix)
            v[static_cast<std::size_t>(iy * nx + ix)] =
                static_cast<float>(ix + 1000 * iy) / static_cast<float>(nx + 1000 * ny);
    return v;
}

}  // namespace

TEST(MapImage, PfmRoundTripIsExact)
{
    test::TempDir dir;
    const std::string path = (dir / "a.tmp").string();  // format never comes from the name
    std::vector<float> v = ramp(7, 5);
    v[3] = -2.5f;
    v[4] = 1e30f;
    v[5] = std::numeric_limits<float>::denorm_min();
    formats::writePfm(path, 7, 5, v);
    const formats::MapImage img = formats::readPfm(path);
    EXPECT_EQ(img.nx, 7);
    EXPECT_EQ(img.ny, 5);
    ASSERT_EQ(img.values.size(), v.size());
    EXPECT_EQ(std::memcmp(img.values.data(), v.data(), v.size() * sizeof(float)), 0);
}

TEST(MapImage, PfmLayoutIsLittleEndianBottomRowFirst)
{
    test::TempDir dir;
    const auto path = dir / "b.pfm";
    // 2 x 2: row iy = 0 holds 1, 2; row iy = 1 holds 3, 4.
    formats::writePfm(path.string(), 2, 2, {1.0f, 2.0f, 3.0f, 4.0f});
    const std::string bytes = test::readFile(path);
    const std::string header = "Pf\n2 2\n-1.0\n";
    ASSERT_EQ(bytes.size(), header.size() + 16);
    EXPECT_EQ(bytes.substr(0, header.size()), header);
    // 1.0f little-endian = 00 00 80 3f, first in the file (bottom row, left).
    EXPECT_EQ(bytes.substr(header.size(), 4), std::string("\x00\x00\x80\x3f", 4));
    // 4.0f = 00 00 80 40, last (top row, right).
    EXPECT_EQ(bytes.substr(header.size() + 12, 4), std::string("\x00\x00\x80\x40", 4));
}

TEST(MapImage, PfmReadsBigEndianToo)
{
    test::TempDir dir;
    const auto path = dir / "be.pfm";
    test::writeFile(path, std::string("Pf\n1 1\n1.0\n") + std::string("\x3f\x80\x00\x00", 4));
    const formats::MapImage img = formats::readPfm(path.string());
    EXPECT_EQ(img.values, std::vector<float>{1.0f});
}

TEST(MapImage, MalformedPfmIsRefusedWithTheFileName)
{
    test::TempDir dir;
    const std::string data16(16, '\0');
    const std::vector<std::string> bad = {
        "",
        "P5\n2 2\n255\n" + data16,                     // not a PFM
        "PF\n2 2\n-1.0\n" + data16,                    // colour
        "Pf\n2 2\n-1.0\n" + data16.substr(0, 15),      // short
        "Pf\n2 2\n-1.0\n" + data16 + "x",              // trailing bytes
        "Pf\n0 2\n-1.0\n",                             // zero width
        "Pf\n-2 2\n-1.0\n" + data16,                   // negative width
        "Pf\n2 2\n0\n" + data16,                       // zero scale
        "Pf\n2 2\nabc\n" + data16,                     // bad scale
        "Pf\n99999999999 2\n-1.0\n" + data16,          // overflow
        "Pf\n4294967296 4294967296\n-1.0\n" + data16,  // huge, refused before allocating
        "Pf\n2 2\n-1.0",                               // header not terminated
    };
    for (std::size_t i = 0; i < bad.size(); ++i) {
        const auto path = dir / ("bad" + std::to_string(i) + ".pfm");
        test::writeFile(path, bad[i]);
        try {
            formats::readPfm(path.string());
            ADD_FAILURE() << "case " << i << " was accepted";
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
        }
    }
    EXPECT_THROW(formats::readPfm((dir / "missing.pfm").string()), std::runtime_error);
}

TEST(MapImage, WritersRefuseMismatchedSizes)
{
    test::TempDir dir;
    EXPECT_THROW(formats::writePfm((dir / "x").string(), 3, 3, std::vector<float>(8)),
                 std::invalid_argument);
    EXPECT_THROW(formats::writePng16((dir / "y").string(), 0, 3, {}), std::invalid_argument);
    EXPECT_THROW(formats::writePfm((dir / "no/such/dir/x").string(), 1, 1, {0.0f}),
                 std::runtime_error);
    EXPECT_THROW(formats::writePng16((dir / "no/such/dir/y").string(), 1, 1, {0.0f}),
                 std::runtime_error);
}

TEST(MapImage, Png16RoundTripWithinOneStep)
{
    test::TempDir dir;
    const std::string path = (dir / "c.tmp").string();
    std::vector<float> v = ramp(33, 17);
    formats::writePng16(path, 33, 17, v);
    const formats::MapImage img = formats::readPng16(path);
    EXPECT_EQ(img.nx, 33);
    EXPECT_EQ(img.ny, 17);
    ASSERT_EQ(img.values.size(), v.size());
    for (std::size_t i = 0; i < v.size(); ++i)
        EXPECT_LE(std::abs(img.values[i] - v[i]), 1.0f / 65535.0f) << i;
    EXPECT_EQ(img.values[0], 0.0f);
}

TEST(MapImage, Png16ClampsAndKeepsOrientation)
{
    test::TempDir dir;
    const std::string path = (dir / "d.png").string();
    // Row iy = 0 (bottom) = {-1, 0.5}; row iy = 1 (top) = {2, NaN}.
    formats::writePng16(path, 2, 2, {-1.0f, 0.5f, 2.0f, std::nanf("")});
    const formats::MapImage img = formats::readPng16(path);
    ASSERT_EQ(img.values.size(), 4u);
    EXPECT_EQ(img.values[0], 0.0f);
    EXPECT_NEAR(img.values[1], 0.5f, 1.0f / 65535.0f);
    EXPECT_EQ(img.values[2], 1.0f);
    EXPECT_EQ(img.values[3], 0.0f);
    // A real PNG, whatever the (temp) name.
    const std::string bytes = test::readFile(path);
    EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
}

TEST(MapImage, ReadPng16RefusesOtherFiles)
{
    test::TempDir dir;
    const auto path = dir / "e.png";
    test::writeFile(path, "not a png at all");
    EXPECT_THROW(formats::readPng16(path.string()), std::runtime_error);
    test::writeFile(path, std::string("\x89PNG\r\n\x1a\n", 8) + "truncated");
    EXPECT_THROW(formats::readPng16(path.string()), std::runtime_error);
}

}  // namespace cg
