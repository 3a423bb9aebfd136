#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/CacheBound.h"
#include "core/CoreData.h"
#include "core/DiskCache.h"
#include "core/Error.h"
#include "core/Registry.h"
#include "support/TestUtil.h"

namespace cg {

namespace fs = std::filesystem;

namespace {

Key keyOf(std::uint64_t i) { return Key{0xC0FFEE00ull + i, i * 0x9E3779B97F4A7C15ull + 1}; }

/// Stores entry i holding `floats` floats, last used `age` hours ago.
void storeAged(const DiskCache& cache, std::uint64_t i, std::size_t floats, int age)
{
    OutputMap outputs;
    outputs["v"] = std::make_shared<FloatArrayData>(std::vector<float>(floats, 1.0f));
    ASSERT_TRUE(cache.store(keyOf(i), outputs));
    fs::last_write_time(cache.entryPath(keyOf(i)),
                        fs::file_time_type::clock::now() - std::chrono::hours(age));
}

std::uint64_t entryBytes(const DiskCache& cache, std::uint64_t i)
{
    return fs::file_size(cache.entryPath(keyOf(i)));
}

}  // namespace

TEST(CacheBound, UsageCountsEveryEntryAndNothingElse)
{
    test::TempDir dir;
    EXPECT_EQ(cacheUsage(dir.path()).entries, 0u);  // no cache yet: nothing, no error
    DiskCache cache(dir.path());
    for (std::uint64_t i = 0; i < 5; ++i) storeAged(cache, i, 100 * (i + 1), 1);
    cache.storeRecord("writer", nlohmann::json{{"files", 3}});
    std::uint64_t expected = 0;
    for (std::uint64_t i = 0; i < 5; ++i) expected += entryBytes(cache, i);
    const CacheUsage usage = cacheUsage(dir.path());
    EXPECT_EQ(usage.entries, 5u);
    EXPECT_EQ(usage.bytes, expected);
}

TEST(CacheBound, PruningRemovesTheLeastRecentlyUsedUntilTheRestFits)
{
    test::TempDir dir;
    DiskCache cache(dir.path());
    // Entry i was last used 10 - i hours ago: entry 0 is the oldest.
    for (std::uint64_t i = 0; i < 6; ++i) storeAged(cache, i, 1000, 10 - static_cast<int>(i));
    const std::uint64_t each = entryBytes(cache, 0);
    const CacheUsage removed = pruneCache(dir.path(), 3 * each + each / 2);
    EXPECT_EQ(removed.entries, 3u);
    EXPECT_EQ(removed.bytes, 3 * each);
    for (std::uint64_t i = 0; i < 6; ++i)
        EXPECT_EQ(cache.contains(keyOf(i)), i >= 3) << "entry " << i;
    EXPECT_EQ(cacheUsage(dir.path()).bytes, 3 * each);
    EXPECT_EQ(pruneCache(dir.path(), 3 * each).entries, 0u);  // already within the bound
    EXPECT_EQ(pruneCache(dir.path(), 0).entries, 3u);
    EXPECT_EQ(cacheUsage(dir.path()).entries, 0u);
}

TEST(CacheBound, ALoadMakesAnEntryRecentlyUsedSoPruningKeepsIt)
{
    test::TempDir dir;
    DiskCache cache(dir.path());
    Registry registry;
    registerCoreDataTypes(registry);
    for (std::uint64_t i = 0; i < 4; ++i) storeAged(cache, i, 500, 10 - static_cast<int>(i));
    ASSERT_TRUE(cache.load(keyOf(0), registry).has_value());  // the oldest, read just now
    pruneCache(dir.path(), 2 * entryBytes(cache, 0));
    EXPECT_TRUE(cache.contains(keyOf(0)));
    EXPECT_FALSE(cache.contains(keyOf(1)));
    EXPECT_FALSE(cache.contains(keyOf(2)));
    EXPECT_TRUE(cache.contains(keyOf(3)));
    const auto reloaded = cache.load(keyOf(0), registry);  // what stays is whole
    ASSERT_TRUE(reloaded.has_value());
    EXPECT_EQ(dynamic_cast<const FloatArrayData&>(*reloaded->at("v")).values.size(), 500u);
}

TEST(CacheBound, PruningLeavesRecordsAndForeignFilesAlone)
{
    test::TempDir dir;
    DiskCache cache(dir.path());
    storeAged(cache, 1, 100, 5);
    cache.storeRecord("writer", nlohmann::json{{"files", 1}});
    {
        std::ofstream(dir.path() / "objects" / "notes.txt") << "mine";
    }
    pruneCache(dir.path(), 0);
    EXPECT_FALSE(cache.contains(keyOf(1)));
    EXPECT_TRUE(cache.loadRecord("writer").has_value());
    EXPECT_TRUE(fs::exists(dir.path() / "objects" / "notes.txt"));
}

TEST(CacheBound, SizesReadAsAPersonWritesThem)
{
    EXPECT_EQ(parseByteSize("800000", "--cache-limit"), 800000u);
    EXPECT_EQ(parseByteSize("512K", "--cache-limit"), 512u << 10);
    EXPECT_EQ(parseByteSize("500M", "--cache-limit"), 500ull << 20);
    EXPECT_EQ(parseByteSize("2G", "--cache-limit"), 2ull << 30);
    EXPECT_EQ(parseByteSize("2gib", "--cache-limit"), 2ull << 30);
    EXPECT_EQ(parseByteSize("1.5GB", "--cache-limit"), 3ull << 29);
    EXPECT_EQ(parseByteSize("1T", "--cache-limit"), 1ull << 40);
    for (const char* bad : {"", "G", "-1G", "2X", "2GG", "nan", "inf", "1e30T", "20 G"}) {
        try {
            parseByteSize(bad, "--cache-limit");
            ADD_FAILURE() << "'" << bad << "' was taken";
        } catch (const InputError& e) {
            EXPECT_EQ(e.where(), "--cache-limit") << bad;
        }
    }
}

}  // namespace cg
