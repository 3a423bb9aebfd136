// Fuzz target: the primitive-set reader (.cgp, formats/PrimitiveFile.h). The input is a
// whole file whose checksums are then made valid, as a forged file's would be, so the fuzzer
// reaches the index and frame checks behind them. Every rejection must be a
// cg::formats::FormatError, and a file that opens must yield every position it declares.
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "core/Hash.h"
#include "formats/FormatError.h"
#include "formats/PrimitiveFile.h"

namespace {

using cg::formats::kPrimitiveHeaderBytes;
using cg::formats::kPrimitiveIndexEntryBytes;

constexpr std::size_t kHeaderChecksumAt = 56;

std::uint32_t getU32(const unsigned char* p)
{
    return std::uint32_t{p[0]} | std::uint32_t{p[1]} << 8 | std::uint32_t{p[2]} << 16 |
           std::uint32_t{p[3]} << 24;
}

void putU64(unsigned char* p, std::uint64_t v)
{
    for (int k = 0; k < 8; ++k) p[k] = static_cast<unsigned char>(v >> (8 * k));
}

/// Writes the header checksum and every block checksum that lies inside the file.
void forgeChecksums(std::vector<unsigned char>& f)
{
    if (f.size() < kPrimitiveHeaderBytes) return;
    const std::uint64_t frames = getU32(f.data() + 12);
    const std::uint64_t indexEnd = kPrimitiveHeaderBytes + kPrimitiveIndexEntryBytes * frames;
    if (indexEnd > f.size()) return;
    std::vector<unsigned char> checked(f.begin(), f.begin() + kHeaderChecksumAt);
    checked.insert(checked.end(), f.begin() + kPrimitiveHeaderBytes, f.begin() + indexEnd);
    putU64(f.data() + kHeaderChecksumAt, cg::checksum64(checked.data(), checked.size()));

    std::uint64_t at = indexEnd;
    for (std::uint64_t s = 0; s < frames; ++s) {
        const std::uint64_t n =
            getU32(f.data() + kPrimitiveHeaderBytes + kPrimitiveIndexEntryBytes * s + 8);
        const std::uint64_t body = 8 + 12 * n;
        if (body + 8 > f.size() - at) return;
        putU64(f.data() + at + body, cg::checksum64(f.data() + at, body));
        at += body + 8;
    }
}

/// The reader only opens paths: each input goes into one memory file per process (no file on
/// disk to clean up, and fast), opened again by the reader through /proc/self/fd.
const std::string& memoryFile(const std::vector<unsigned char>& bytes)
{
    static const int fd = ::memfd_create("fuzz.cgp", MFD_CLOEXEC);
    static const std::string path = "/proc/self/fd/" + std::to_string(fd);
    if (fd < 0 || ::ftruncate(fd, 0) != 0 ||
        ::pwrite(fd, bytes.data(), bytes.size(), 0) != static_cast<ssize_t>(bytes.size()))
        std::abort();  // the harness's own failure, not a finding
    return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    std::vector<unsigned char> file(data, data + size);
    forgeChecksums(file);
    const std::string& path = memoryFile(file);
    try {
        cg::formats::PrimitiveFileReader reader(path);
        const std::vector<float> all = reader.readAll();
        std::uint64_t total = 0;
        for (std::uint32_t n : reader.counts()) total += n;
        if (all.size() != 3 * total) std::abort();  // readAll must return every position
        cg::formats::primitiveFileContentHash(path);
    } catch (const cg::formats::FormatError&) {
    }
    return 0;
}
