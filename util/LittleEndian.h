#pragma once
/// Little-endian packing of integers and floats, byte by byte so that every file and cache
/// entry we write reads the same on any host. The one implementation for every format.

#include <cstdint>
#include <cstring>

namespace cg::util {

inline void putU32(unsigned char* p, std::uint32_t v)
{
    for (int i = 0; i < 4; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}
inline void putU64(unsigned char* p, std::uint64_t v)
{
    for (int i = 0; i < 8; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}
inline void putF32(unsigned char* p, float v)
{
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    putU32(p, bits);
}
inline void putF64(unsigned char* p, double v)
{
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    putU64(p, bits);
}

inline std::uint32_t getU32(const unsigned char* p)
{
    return std::uint32_t{p[0]} | std::uint32_t{p[1]} << 8 | std::uint32_t{p[2]} << 16 |
           std::uint32_t{p[3]} << 24;
}
inline std::uint64_t getU64(const unsigned char* p)
{
    return std::uint64_t{getU32(p)} | std::uint64_t{getU32(p + 4)} << 32;
}
inline float getF32(const unsigned char* p)
{
    const std::uint32_t bits = getU32(p);
    float v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
}
inline double getF64(const unsigned char* p)
{
    const std::uint64_t bits = getU64(p);
    double v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
}

/// Appends the little-endian bytes of `v` to a byte string or vector.
template <class Bytes>
void appendU32(Bytes& out, std::uint32_t v)
{
    unsigned char b[4];
    putU32(b, v);
    out.insert(out.end(), b, b + 4);
}
template <class Bytes>
void appendU64(Bytes& out, std::uint64_t v)
{
    unsigned char b[8];
    putU64(b, v);
    out.insert(out.end(), b, b + 8);
}

template <class Bytes>
void appendF32(Bytes& out, float v)
{
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    appendU32(out, bits);
}
template <class Bytes>
void appendF64(Bytes& out, double v)
{
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    appendU64(out, bits);
}

}  // namespace cg::util
