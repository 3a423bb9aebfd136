#include "formats/MapFile.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>

#include "formats/ExrFile.h"
#include "formats/FormatError.h"
#include "formats/PngFile.h"
#include "util/InputFile.h"

namespace cg::formats {

namespace {

enum class MapFormat { Png, Pfm, Exr };

/// The format the file's first bytes say; FormatError for none of ours.
MapFormat sniff(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    char magic[8] = {};
    in.read(magic, sizeof magic);
    const std::size_t got = static_cast<std::size_t>(in.gcount());
    if (got >= 8 && std::memcmp(magic, "\x89PNG\r\n\x1a\n", 8) == 0) return MapFormat::Png;
    if (got >= 2 && magic[0] == 'P' && (magic[1] == 'f' || magic[1] == 'F')) return MapFormat::Pfm;
    if (got >= 4 && std::memcmp(magic, "\x76\x2f\x31\x01", 4) == 0) return MapFormat::Exr;
    throw FormatError(path.string(), "not a PNG, PFM or OpenEXR image");
}

MapImage fromPng(const std::filesystem::path& path, std::uint64_t maxPixels)
{
    const PngPixels px = readPng(path.string(), 0, 0, kMaxMapSide);
    if (static_cast<std::uint64_t>(px.width) * static_cast<std::uint64_t>(px.height) > maxPixels)
        throw FormatError(path.string(), "more pixels than a map may have");
    const double top = px.bitDepth == 16 ? 65535.0 : 255.0;
    const std::size_t bytesPerSample = px.bitDepth == 16 ? 2 : 1;
    const auto sample = [&](std::size_t i) {
        const unsigned char* b = &px.bytes[i * bytesPerSample];
        return (bytesPerSample == 2 ? (unsigned(b[0]) << 8) | b[1] : b[0]) / top;
    };
    MapImage map;
    map.nx = px.width;
    map.ny = px.height;
    map.values.resize(static_cast<std::size_t>(px.width) * static_cast<std::size_t>(px.height));
    for (int r = 0; r < px.height; ++r)
        for (int x = 0; x < px.width; ++x) {
            const std::size_t pixel = static_cast<std::size_t>(r) * px.width + x;
            const double v = px.channels == 1
                                 ? sample(pixel)
                                 : 0.2126 * sample(3 * pixel) + 0.7152 * sample(3 * pixel + 1) +
                                       0.0722 * sample(3 * pixel + 2);
            // PNG rows run top to bottom; the top row is the map's iy = ny - 1.
            const std::size_t iy = static_cast<std::size_t>(px.height - 1 - r);
            map.values[iy * static_cast<std::size_t>(px.width) + x] = static_cast<float>(v);
        }
    return map;
}

MapImage fromExr(const std::filesystem::path& path, std::uint64_t maxPixels)
{
    const ExrChannelImage y = readExrLuminance(path.string(), maxPixels);
    MapImage map;
    map.nx = y.width;
    map.ny = y.height;
    map.values.resize(y.values.size());
    const auto w = static_cast<std::size_t>(y.width);
    for (std::size_t r = 0; r < static_cast<std::size_t>(y.height); ++r)
        std::memcpy(&map.values[(static_cast<std::size_t>(y.height) - 1 - r) * w], &y.values[r * w],
                    w * sizeof(float));
    return map;
}

}  // namespace

MapImage readMapFile(const std::filesystem::path& path, std::uint64_t maxPixels)
{
    // A PFM holds 4 bytes a pixel after a short header; the other formats compress, and
    // their pixel counts are checked from their headers.
    const std::uint64_t maxBytes = std::min<std::uint64_t>(maxPixels, 1ull << 40) * 4 + 4096;
    if (const std::string problem = util::inputFileProblem(path, maxBytes); !problem.empty())
        throw FormatError(path.string(), "cannot read the map: it " + problem);
    MapImage map;
    try {
        switch (sniff(path)) {
            case MapFormat::Png:
                map = fromPng(path, maxPixels);
                break;
            case MapFormat::Pfm:
                map = readPfm(path.string());
                if (map.nx > int(kMaxMapSide) || map.ny > int(kMaxMapSide))
                    throw FormatError(path.string(), "more than 16384 pixels on a side");
                break;
            case MapFormat::Exr:
                map = fromExr(path, maxPixels);
                break;
        }
    } catch (const FormatError&) {
        throw;
    } catch (const std::runtime_error& e) {
        // The readers name the file already.
        const std::string what = e.what();
        const std::string prefix = path.string() + ": ";
        throw FormatError(path.string(),
                          what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what);
    }
    if (map.nx > int(kMaxMapSide) || map.ny > int(kMaxMapSide))
        throw FormatError(path.string(), "more than 16384 pixels on a side");
    for (std::size_t i = 0; i < map.values.size(); ++i)
        if (!std::isfinite(map.values[i]))
            throw FormatError(path.string(), "pixel " + std::to_string(i) + " is not finite");
    return map;
}

}  // namespace cg::formats
