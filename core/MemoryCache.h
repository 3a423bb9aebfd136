#pragma once
/// In-memory cache of cooked outputs by content key: least recently used out first,
/// under a byte budget. Thread-safe. Values are immutable and shared, so an entry
/// evicted while in use stays alive for its users.

#include <cstddef>
#include <list>
#include <memory>
#include <mutex>
#include <unordered_map>

#include "core/Hash.h"
#include "core/Node.h"

namespace cg {

using OutputsPtr = std::shared_ptr<const OutputMap>;

/// Sum of byteSize() over the values.
std::size_t outputBytes(const OutputMap& outputs);

class MemoryCache {
public:
    explicit MemoryCache(std::size_t budgetBytes) : mBudget(budgetBytes) {}

    /// The entry for `key`, made most recently used; nullptr when absent.
    OutputsPtr find(const Key& key);
    /// Inserts (or refreshes) an entry, then evicts least recently used entries until the
    /// total fits the budget. An entry larger than the whole budget is not kept.
    void insert(const Key& key, OutputsPtr outputs);
    void clear();

    std::size_t bytes() const;
    std::size_t entries() const;
    std::size_t budget() const { return mBudget; }

private:
    struct Entry {
        Key key;
        OutputsPtr outputs;
        std::size_t bytes;
    };
    mutable std::mutex mMutex;
    std::size_t mBudget;
    std::size_t mBytes = 0;
    std::list<Entry> mLru;  ///< front = most recently used
    std::unordered_map<Key, std::list<Entry>::iterator, KeyHash> mIndex;
};

}  // namespace cg
