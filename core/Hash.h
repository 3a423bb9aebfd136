#pragma once
/// Content keys and checksums (xxHash XXH3, 128-bit keys, 64-bit checksums).

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace cg {

/// A 128-bit content key. Two outputs with the same key are the same value.
struct Key {
    std::uint64_t hi = 0;
    std::uint64_t lo = 0;

    bool operator==(const Key& o) const { return hi == o.hi && lo == o.lo; }
    bool operator!=(const Key& o) const { return !(*this == o); }
    bool operator<(const Key& o) const { return hi != o.hi ? hi < o.hi : lo < o.lo; }
    bool isNull() const { return hi == 0 && lo == 0; }
    /// 32 lowercase hex digits.
    std::string hex() const;
    /// Parses 32 hex digits; returns false on anything else.
    static bool fromHex(std::string_view text, Key& out);
};

struct KeyHash {
    std::size_t operator()(const Key& k) const { return static_cast<std::size_t>(k.lo ^ k.hi); }
};

/// Incremental hasher for building keys. Every field is tagged with its length, so
/// ("ab","c") and ("a","bc") never hash alike.
class Hasher {
public:
    Hasher();
    ~Hasher();
    Hasher(const Hasher&) = delete;
    Hasher& operator=(const Hasher&) = delete;

    Hasher& bytes(const void* data, std::size_t size);
    Hasher& str(std::string_view s);
    Hasher& u64(std::uint64_t v);
    Hasher& i64(std::int64_t v) { return u64(static_cast<std::uint64_t>(v)); }
    /// Hashes the bit pattern, with -0.0 folded onto +0.0.
    Hasher& f64(double v);
    Hasher& key(const Key& k) { return u64(k.hi).u64(k.lo); }
    Key finish() const;

private:
    void* mState;
};

/// 64-bit checksum of a byte range (XXH3-64).
std::uint64_t checksum64(const void* data, std::size_t size);

}  // namespace cg
