// Fuzz target: the disk-cache entry decoder (cg::DiskCache::decodeEntry) with every built-in
// data type. The input is the payload of a forged entry: the harness prepends a header whose
// key, length and checksums are all valid, so every input reaches the value deserializers, as a
// planted file in a shared cache directory would. Rejection must be a std::runtime_error; a
// value that is accepted must encode into an entry that decodes again.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "core/DiskCache.h"
#include "core/Hash.h"
#include "core/Registry.h"
#include "nodes/Builtin.h"

namespace {

// The entry header of core/DiskCache.cc, format version 1.
constexpr char kMagic[8] = {'C', 'G', 'C', 'A', 'C', 'H', 'E', '1'};
constexpr std::size_t kHeaderSize = 56;
constexpr std::size_t kHeaderChecksumOffset = 48;
const cg::Key kKey{0x0123456789abcdefull, 0xfedcba9876543210ull};

void putU64(unsigned char* p, std::uint64_t v)
{
    for (int i = 0; i < 8; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}

std::vector<unsigned char> forgeEntry(const std::uint8_t* payload, std::size_t size)
{
    std::vector<unsigned char> e(kHeaderSize + size);
    if (size > 0) std::memcpy(e.data() + kHeaderSize, payload, size);
    std::memcpy(e.data(), kMagic, 8);
    putU64(e.data() + 8, 1);  // u32 version 1, then u32 reserved 0
    putU64(e.data() + 16, kKey.hi);
    putU64(e.data() + 24, kKey.lo);
    putU64(e.data() + 32, size);
    putU64(e.data() + 40, cg::checksum64(e.data() + kHeaderSize, size));
    putU64(e.data() + 48, cg::checksum64(e.data(), kHeaderChecksumOffset));
    return e;
}

const cg::Registry& registry()
{
    static const cg::Registry* r = [] {
        auto* reg = new cg::Registry;  // never freed: lives as long as the process
        cg::registerBuiltinNodes(*reg);
        return reg;
    }();
    return *r;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::vector<unsigned char> entry = forgeEntry(data, size);
    cg::OutputMap outputs;
    try {
        outputs = cg::DiskCache::decodeEntry(kKey, entry.data(), entry.size(), registry());
    } catch (const std::runtime_error&) {
        return 0;
    }
    // Outside the try: what was accepted must store and load again. (Bytes may differ: an
    // OpenVDB stream carries a fresh UUID each time it is written.)
    std::vector<unsigned char> again;
    if (cg::DiskCache::encodeEntry(kKey, outputs, again))
        cg::DiskCache::decodeEntry(kKey, again.data(), again.size(), registry());
    return 0;
}
