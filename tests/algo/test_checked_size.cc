// Overflow-checked products of extents (util/CheckedSize.h), which every dense grid of the
// renderer and the voxelizer is sized with.

#include <cstdint>
#include <limits>

#include <gtest/gtest.h>

#include "util/CheckedSize.h"

namespace cg {
namespace {

TEST(CheckedSize, AProductThatWrapsIsNothingNotItsRemainder)
{
    constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();
    EXPECT_EQ(util::checkedMul(1u << 31, 1u << 31), std::uint64_t(1) << 62);
    EXPECT_EQ(util::checkedMul(kMax, 1), kMax);
    EXPECT_FALSE(util::checkedMul(std::uint64_t(1) << 32, std::uint64_t(1) << 32));
    EXPECT_FALSE(util::checkedMul(kMax, 2));
    // 2^22 x 2^21 x 2^21 wraps to exactly 0 in 64 bits, which passes any "at most" check.
    EXPECT_FALSE(util::checkedProduct({1 << 22, 1 << 21, 1 << 21}));
    EXPECT_FALSE(util::productWithin({1 << 22, 1 << 21, 1 << 21}, 1u << 27));
    EXPECT_EQ(util::checkedProduct({1 << 22, 1 << 21, 1 << 20}), std::uint64_t(1) << 63);
    EXPECT_EQ(util::checkedProduct({}), 1u);
    EXPECT_EQ(util::checkedProduct({3, 0, std::int64_t(1) << 62}), 0u);
    EXPECT_FALSE(util::checkedProduct({-1, 4}));
    EXPECT_EQ(util::productWithin({512, 512, 512}, 1u << 27), std::uint64_t(1) << 27);
    EXPECT_FALSE(util::productWithin({512, 512, 513}, 1u << 27));
    EXPECT_EQ(util::extentsText({4194304, 2097152, 2097152}), "4194304 x 2097152 x 2097152");
}

}  // namespace
}  // namespace cg
