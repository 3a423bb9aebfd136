// Fuzz target: the painted-map reader (formats/MapFile.h), PNG, PFM and OpenEXR by their
// first bytes. The reader takes a path, so each input is written to a scratch file first.
// Every rejection must be a cg::formats::FormatError; a map that reads must have a sane
// size, match it, and hold only finite values.
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>

#include "formats/FormatError.h"
#include "formats/MapFile.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    static const std::string path = "/tmp/cloudgraph-fuzz-map-" + std::to_string(::getpid());
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    }
    cg::formats::MapImage map;
    try {
        map = cg::formats::readMapFile(path, std::uint64_t{1} << 22);
    } catch (const cg::formats::FormatError&) {
        return 0;
    }
    if (map.nx < 1 || map.ny < 1 || map.nx > int(cg::formats::kMaxMapSide) ||
        map.ny > int(cg::formats::kMaxMapSide))
        std::abort();
    if (map.values.size() != static_cast<std::size_t>(map.nx) * static_cast<std::size_t>(map.ny))
        std::abort();
    for (float v : map.values)
        if (!std::isfinite(v)) std::abort();
    return 0;
}
