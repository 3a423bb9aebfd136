#pragma once
/// Values that travel along ports. A Data is immutable once made and shared by pointer;
/// a node that wants to modify an input copies it first.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "util/LittleEndian.h"

namespace cg {

/// Little-endian byte sink for the disk cache.
class ByteWriter {
public:
    ByteWriter() = default;
    /// Appends to `buffer` (whose capacity a caller may reuse).
    explicit ByteWriter(std::vector<unsigned char> buffer) : mBuf(std::move(buffer)) {}

    void bytes(const void* data, std::size_t size)
    {
        const auto* p = static_cast<const unsigned char*>(data);
        mBuf.insert(mBuf.end(), p, p + size);
    }
    void u64(std::uint64_t v)
    {
        unsigned char b[8];
        util::putU64(b, v);
        bytes(b, 8);
    }
    void f64(double v)
    {
        std::uint64_t bits;
        std::memcpy(&bits, &v, 8);
        u64(bits);
    }
    void str(std::string_view s)
    {
        u64(s.size());
        bytes(s.data(), s.size());
    }
    template <class T>
    void podVector(const std::vector<T>& v)
    {
        u64(v.size());
        bytes(v.data(), v.size() * sizeof(T));
    }
    std::vector<unsigned char>& buffer() { return mBuf; }

private:
    std::vector<unsigned char> mBuf;
};

/// Reads what ByteWriter wrote; throws std::runtime_error on any overrun, so a damaged
/// payload never makes a wrong value or an absurd allocation.
class ByteReader {
public:
    ByteReader(const unsigned char* data, std::size_t size) : mData(data), mSize(size) {}
    void bytes(void* out, std::size_t size);
    std::uint64_t u64();
    double f64();
    std::string str();
    template <class T>
    std::vector<T> podVector()
    {
        const std::uint64_t n = u64();
        if (n > remaining() / sizeof(T)) overrun();
        std::vector<T> v(static_cast<std::size_t>(n));
        bytes(v.data(), v.size() * sizeof(T));
        return v;
    }
    std::size_t remaining() const { return mSize - mPos; }
    bool atEnd() const { return mPos == mSize; }

private:
    [[noreturn]] void overrun() const;
    const unsigned char* mData;
    std::size_t mSize;
    std::size_t mPos = 0;
};

class Data {
public:
    virtual ~Data() = default;
    /// The port type this value carries, e.g. "Float" or "Map2D".
    virtual std::string typeName() const = 0;
    /// Approximate memory held, for the cache's byte budget.
    virtual std::size_t byteSize() const = 0;
    /// Writes the value for the disk cache. Types that cannot be stored return false.
    virtual bool serialize(ByteWriter& out) const = 0;
};

using DataPtr = std::shared_ptr<const Data>;

/// How to rebuild a stored value of one port type.
struct DataTypeInfo {
    std::string name;
    std::string doc;
    /// Rebuilds a value from serialize()'s bytes; throws on malformed bytes.
    DataPtr (*deserialize)(ByteReader& in) = nullptr;
};

}  // namespace cg
