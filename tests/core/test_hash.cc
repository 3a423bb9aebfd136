#include <gtest/gtest.h>

#include "core/Hash.h"

namespace cg {

TEST(Hash, FieldsAreLengthTagged)
{
    Hasher a, b;
    a.str("ab").str("c");
    b.str("a").str("bc");
    EXPECT_NE(a.finish(), b.finish());
}

TEST(Hash, NegativeZeroHashesAsZero)
{
    Hasher a, b;
    a.f64(0.0);
    b.f64(-0.0);
    EXPECT_EQ(a.finish(), b.finish());
}

TEST(Hash, HexRoundTrip)
{
    Hasher h;
    h.str("cloud");
    const Key k = h.finish();
    Key back;
    ASSERT_TRUE(Key::fromHex(k.hex(), back));
    EXPECT_EQ(k, back);
    EXPECT_FALSE(Key::fromHex("xyz", back));
    EXPECT_FALSE(Key::fromHex(std::string(32, 'G'), back));
}

TEST(Hash, ChecksumSeesOneFlippedBit)
{
    std::string s(1000, 'a');
    const auto before = checksum64(s.data(), s.size());
    s[500] ^= 1;
    EXPECT_NE(before, checksum64(s.data(), s.size()));
}

}  // namespace cg
