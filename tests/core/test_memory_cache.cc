#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <thread>
#include <vector>

#include "core/CoreData.h"
#include "core/MemoryCache.h"

namespace cg {

namespace {

Key keyOf(std::uint64_t i) { return Key{i + 1, i * 7919 + 3}; }

/// Outputs holding `floats` floats, so their byte size is known.
OutputsPtr makeOutputs(std::size_t floats, float fill = 1.0f)
{
    auto map = std::make_shared<OutputMap>();
    (*map)["out"] = std::make_shared<FloatArrayData>(std::vector<float>(floats, fill));
    return map;
}

std::size_t sizeOf(std::size_t floats) { return outputBytes(*makeOutputs(floats)); }

}  // namespace

TEST(MemoryCache, OutputBytesSumsByteSizes)
{
    OutputMap m;
    m["a"] = std::make_shared<FloatArrayData>(std::vector<float>(100));
    m["b"] = std::make_shared<TextData>(std::string(50, 'x'));
    m["c"] = std::make_shared<FloatData>(1.0);
    EXPECT_EQ(outputBytes(m), m["a"]->byteSize() + m["b"]->byteSize() + m["c"]->byteSize());
    EXPECT_GE(outputBytes(m), 100 * sizeof(float) + 50);
    EXPECT_EQ(outputBytes(OutputMap{}), 0u);
}

TEST(MemoryCache, FindAfterInsertReturnsSamePointer)
{
    MemoryCache cache(1 << 20);
    const OutputsPtr a = makeOutputs(10);
    const OutputsPtr b = makeOutputs(20);
    cache.insert(keyOf(0), a);
    cache.insert(keyOf(1), b);
    EXPECT_EQ(cache.find(keyOf(0)).get(), a.get());
    EXPECT_EQ(cache.find(keyOf(1)).get(), b.get());
    EXPECT_EQ(cache.find(keyOf(2)), nullptr);
    EXPECT_EQ(cache.entries(), 2u);
    EXPECT_EQ(cache.bytes(), outputBytes(*a) + outputBytes(*b));
}

TEST(MemoryCache, ReinsertReplacesAndKeepsAccounting)
{
    MemoryCache cache(1 << 20);
    cache.insert(keyOf(0), makeOutputs(10));
    const OutputsPtr bigger = makeOutputs(1000);
    cache.insert(keyOf(0), bigger);
    EXPECT_EQ(cache.entries(), 1u);
    EXPECT_EQ(cache.bytes(), outputBytes(*bigger));
    EXPECT_EQ(cache.find(keyOf(0)).get(), bigger.get());
}

TEST(MemoryCache, EvictsLeastRecentlyUsed)
{
    const std::size_t one = sizeOf(1000);
    MemoryCache cache(3 * one);  // room for exactly three entries
    cache.insert(keyOf(0), makeOutputs(1000));
    cache.insert(keyOf(1), makeOutputs(1000));
    cache.insert(keyOf(2), makeOutputs(1000));
    ASSERT_EQ(cache.entries(), 3u);

    // Touch 0: now 1 is the least recently used and goes first.
    ASSERT_NE(cache.find(keyOf(0)), nullptr);
    cache.insert(keyOf(3), makeOutputs(1000));
    EXPECT_EQ(cache.entries(), 3u);
    EXPECT_NE(cache.find(keyOf(0)), nullptr);
    EXPECT_EQ(cache.find(keyOf(1)), nullptr);
    EXPECT_NE(cache.find(keyOf(2)), nullptr);
    EXPECT_NE(cache.find(keyOf(3)), nullptr);

    // Order is now 3, 2, 0 (most recent first); inserting evicts 0.
    cache.insert(keyOf(4), makeOutputs(1000));
    EXPECT_EQ(cache.find(keyOf(0)), nullptr);
    EXPECT_NE(cache.find(keyOf(2)), nullptr);
}

TEST(MemoryCache, NeverExceedsBudget)
{
    const std::size_t budget = 10 * sizeOf(1000);
    MemoryCache cache(budget);
    for (std::uint64_t i = 0; i < 200; ++i) {
        cache.insert(keyOf(i), makeOutputs(200 + (i * 37) % 1700));
        ASSERT_LE(cache.bytes(), budget) << "after insert " << i;
        ASSERT_GT(cache.entries(), 0u);
        // The entry just inserted fits, so it is kept.
        ASSERT_NE(cache.find(keyOf(i)), nullptr);
    }
}

TEST(MemoryCache, EntryLargerThanBudgetIsNotKept)
{
    MemoryCache cache(sizeOf(1000));
    const OutputsPtr small = makeOutputs(10);
    cache.insert(keyOf(0), small);
    cache.insert(keyOf(1), makeOutputs(5000));
    EXPECT_EQ(cache.find(keyOf(1)), nullptr);
    EXPECT_LE(cache.bytes(), cache.budget());
    // The oversized entry did not flush the others.
    EXPECT_EQ(cache.find(keyOf(0)).get(), small.get());

    // Refreshing a key with an oversized value drops the old value too.
    cache.insert(keyOf(0), makeOutputs(5000));
    EXPECT_EQ(cache.find(keyOf(0)), nullptr);
    EXPECT_EQ(cache.bytes(), 0u);
    EXPECT_EQ(cache.entries(), 0u);
}

TEST(MemoryCache, EvictedValuesStayAliveForHolders)
{
    MemoryCache cache(sizeOf(1000));
    OutputsPtr held = makeOutputs(1000, 42.0f);
    const std::weak_ptr<const OutputMap> watch = held;
    cache.insert(keyOf(0), held);
    held.reset();
    OutputsPtr user = cache.find(keyOf(0));
    ASSERT_NE(user, nullptr);

    cache.insert(keyOf(1), makeOutputs(1000));  // evicts key 0
    EXPECT_EQ(cache.find(keyOf(0)), nullptr);
    ASSERT_FALSE(watch.expired());
    const auto* arr = dynamic_cast<const FloatArrayData*>(user->at("out").get());
    ASSERT_NE(arr, nullptr);
    EXPECT_EQ(arr->values.size(), 1000u);
    EXPECT_EQ(arr->values[999], 42.0f);

    user.reset();
    EXPECT_TRUE(watch.expired());  // the cache no longer holds it either
}

TEST(MemoryCache, ClearDropsEverything)
{
    MemoryCache cache(1 << 20);
    cache.insert(keyOf(0), makeOutputs(10));
    cache.insert(keyOf(1), makeOutputs(10));
    cache.clear();
    EXPECT_EQ(cache.entries(), 0u);
    EXPECT_EQ(cache.bytes(), 0u);
    EXPECT_EQ(cache.find(keyOf(0)), nullptr);
}

TEST(MemoryCache, ConcurrentUseKeepsBudget)
{
    const std::size_t budget = 8 * sizeOf(500);
    MemoryCache cache(budget);
    std::atomic<bool> over{false};
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t) {
        threads.emplace_back([&, t] {
            for (std::uint64_t i = 0; i < 500; ++i) {
                const Key k = keyOf((i * 4 + static_cast<std::uint64_t>(t)) % 40);
                if (i % 3 == 0) {
                    cache.insert(k, makeOutputs(100 + (i % 400)));
                } else if (OutputsPtr p = cache.find(k)) {
                    if (p->count("out") != 1) over = true;
                }
                if (cache.bytes() > budget) over = true;
            }
        });
    }
    for (auto& th : threads) th.join();
    EXPECT_FALSE(over.load());
    EXPECT_LE(cache.bytes(), budget);
}

}  // namespace cg
