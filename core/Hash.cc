#include "core/Hash.h"
#include "util/LittleEndian.h"

#include <cstring>

#include <xxhash.h>

namespace cg {

namespace {
XXH3_state_t* state(void* p) { return static_cast<XXH3_state_t*>(p); }
}  // namespace

std::string Key::hex() const
{
    static const char* digits = "0123456789abcdef";
    std::string out(32, '0');
    for (int i = 0; i < 16; ++i) {
        out[static_cast<std::size_t>(15 - i)] = digits[(hi >> (4 * i)) & 0xf];
        out[static_cast<std::size_t>(31 - i)] = digits[(lo >> (4 * i)) & 0xf];
    }
    return out;
}

bool Key::fromHex(std::string_view text, Key& out)
{
    if (text.size() != 32) return false;
    std::uint64_t parts[2] = {0, 0};
    for (std::size_t i = 0; i < 32; ++i) {
        const char c = text[i];
        std::uint64_t d;
        if (c >= '0' && c <= '9')
            d = static_cast<std::uint64_t>(c - '0');
        else if (c >= 'a' && c <= 'f')
            d = static_cast<std::uint64_t>(c - 'a') + 10;
        else
            return false;
        parts[i / 16] = (parts[i / 16] << 4) | d;
    }
    out.hi = parts[0];
    out.lo = parts[1];
    return true;
}

Hasher::Hasher() : mState(XXH3_createState()) { XXH3_128bits_reset(state(mState)); }

Hasher::~Hasher() { XXH3_freeState(state(mState)); }

Hasher& Hasher::bytes(const void* data, std::size_t size)
{
    XXH3_128bits_update(state(mState), data, size);
    return *this;
}

Hasher& Hasher::str(std::string_view s)
{
    u64(s.size());
    return bytes(s.data(), s.size());
}

Hasher& Hasher::u64(std::uint64_t v)
{
    unsigned char b[8];
    util::putU64(b, v);
    return bytes(b, sizeof b);
}

Hasher& Hasher::f64(double v)
{
    if (v == 0.0) v = 0.0;
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    return u64(bits);
}

Key Hasher::finish() const
{
    const XXH128_hash_t h = XXH3_128bits_digest(state(mState));
    return Key{h.high64, h.low64};
}

std::uint64_t checksum64(const void* data, std::size_t size) { return XXH3_64bits(data, size); }

}  // namespace cg
