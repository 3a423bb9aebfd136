#include "core/MemoryCache.h"

#include <iterator>
#include <utility>

namespace cg {

std::size_t outputBytes(const OutputMap& outputs)
{
    std::size_t total = 0;
    for (const auto& [name, value] : outputs) {
        if (value) total += value->byteSize();
    }
    return total;
}

OutputsPtr MemoryCache::find(const Key& key)
{
    std::lock_guard<std::mutex> lock(mMutex);
    auto it = mIndex.find(key);
    if (it == mIndex.end()) return nullptr;
    // Move to the front: most recently used.
    mLru.splice(mLru.begin(), mLru, it->second);
    return it->second->outputs;
}

void MemoryCache::insert(const Key& key, OutputsPtr outputs)
{
    if (!outputs) return;
    const std::size_t size = outputBytes(*outputs);

    // Released outside the lock: destroying large values should not block other threads.
    std::list<Entry> dropped;
    {
        std::lock_guard<std::mutex> lock(mMutex);
        auto it = mIndex.find(key);
        if (it != mIndex.end()) {
            mBytes -= it->second->bytes;
            dropped.splice(dropped.end(), mLru, it->second);
            mIndex.erase(it);
        }
        if (size > mBudget) return;  // would evict everything and still not fit

        mLru.push_front(Entry{key, std::move(outputs), size});
        mIndex.emplace(key, mLru.begin());
        mBytes += size;

        while (mBytes > mBudget && !mLru.empty()) {
            auto last = std::prev(mLru.end());
            mBytes -= last->bytes;
            mIndex.erase(last->key);
            dropped.splice(dropped.end(), mLru, last);
        }
    }
}

void MemoryCache::clear()
{
    std::list<Entry> dropped;
    {
        std::lock_guard<std::mutex> lock(mMutex);
        dropped.swap(mLru);
        mIndex.clear();
        mBytes = 0;
    }
}

std::size_t MemoryCache::bytes() const
{
    std::lock_guard<std::mutex> lock(mMutex);
    return mBytes;
}

std::size_t MemoryCache::entries() const
{
    std::lock_guard<std::mutex> lock(mMutex);
    return mLru.size();
}

}  // namespace cg
