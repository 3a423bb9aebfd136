// RecentLookup: the direct-mapped cache in front of the voxelizer's hash maps.
#include <gtest/gtest.h>

#include <cstdint>
#include <unordered_map>

#include "algo/volume/RecentLookup.h"

namespace cg {
namespace {

TEST(RecentLookup, AnswersEveryKeyWithItsOwnValueAndFetchesOnlyOnAMiss)
{
    std::unordered_map<std::uint64_t, int> map;
    int fetches = 0;
    algo::RecentLookup<int, 2> recent;  // 4 slots: many keys share one
    auto get = [&](std::uint64_t key) {
        return recent.get(key, [&] {
            ++fetches;
            return &map[key];
        });
    };
    // 0 is a key like any other (the empty slot's key is 0 too).
    for (std::uint64_t key = 0; key < 64; ++key) *get(key) = static_cast<int>(key) + 1;
    EXPECT_EQ(fetches, 64);
    for (std::uint64_t key = 0; key < 64; ++key)
        EXPECT_EQ(*get(key), static_cast<int>(key) + 1) << key;
    for (const auto& [key, value] : map) EXPECT_EQ(value, static_cast<int>(key) + 1);

    // A key just asked for is answered from the cache; clear() forgets it.
    get(7);
    fetches = 0;
    EXPECT_EQ(*get(7), 8);
    EXPECT_EQ(fetches, 0);
    recent.clear();
    EXPECT_EQ(*get(7), 8);
    EXPECT_EQ(fetches, 1);
}

}  // namespace
}  // namespace cg
