#pragma once
/// A small direct-mapped cache in front of a hash map, for accumulators that look a cell or
/// block up for every particle: the particles of a copy stream in an order unrelated to
/// space, but fall in a few dozen cells, so most lookups are answered here with one multiply
/// and one compare instead of a hash map probe. No engine includes.

#include <array>
#include <cstdint>

namespace cg::algo {

template <typename T, int Log2Slots = 7>
class RecentLookup {
public:
    /// The value of `key`: from the cache, or from `fetch()` (which must return the map's
    /// stable pointer for the key), remembered for the next time.
    template <typename Fetch>
    T* get(std::uint64_t key, Fetch&& fetch)
    {
        // Fibonacci hashing: the top bits of key * 2^64 / phi spread neighbouring keys.
        Slot& slot = mSlots[(key * 0x9e3779b97f4a7c15ull) >> (64 - Log2Slots)];
        if (slot.value == nullptr || slot.key != key) {
            slot.value = fetch();
            slot.key = key;
        }
        return slot.value;
    }

    /// Forgets every pointer (call when the map's values go away).
    void clear() { mSlots.fill(Slot{}); }

private:
    struct Slot {
        std::uint64_t key = 0;
        T* value = nullptr;
    };
    std::array<Slot, std::size_t(1) << Log2Slots> mSlots{};
};

}  // namespace cg::algo
