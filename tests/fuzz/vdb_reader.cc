// Fuzz target: the VDB fog-volume reader (formats/VdbFile.h) behind ReadVDB. The input is a
// whole .vdb file; the reader lists its grids and reads grid "density" with a 256 MiB limit.
// Every rejection must be a cg::formats::FormatError; a grid that reads is a fog volume
// (named "density", background 0, finite values of 0 or more).
#include <sys/mman.h>
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "formats/FormatError.h"
#include "formats/VdbFile.h"

namespace {

constexpr std::uint64_t kLimit = std::uint64_t{256} << 20;

/// The reader opens paths only: each input goes into one memory file per process, opened
/// again through /proc/self/fd.
const std::string& memoryFile(const std::uint8_t* data, std::size_t size)
{
    static const int fd = ::memfd_create("fuzz.vdb", MFD_CLOEXEC);
    static const std::string path = "/proc/self/fd/" + std::to_string(fd);
    if (fd < 0 || ::ftruncate(fd, 0) != 0 ||
        ::pwrite(fd, data, size, 0) != static_cast<ssize_t>(size))
        std::abort();  // the harness's own failure, not a finding
    return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string& path = memoryFile(data, size);
    try {
        cg::formats::listVdbGrids(path, kLimit);
    } catch (const cg::formats::FormatError&) {
    }
    try {
        const auto grid = cg::formats::readVdbFogVolume(path, "density", kLimit);
        if (grid->getName() != "density" || grid->background() != 0.0f) std::abort();
        for (auto it = grid->cbeginValueAll(); it; ++it)
            if (!std::isfinite(*it) || *it < 0.0f) std::abort();
    } catch (const cg::formats::FormatError&) {
    }
    return 0;
}
