#include "cli/PaintedMap.h"

#include <fcntl.h>
#include <unistd.h>
#include <cerrno>
#include <cstring>
#include <vector>

#include "core/Error.h"
#include "formats/PngFile.h"

namespace cg::cli {

namespace {

namespace fs = std::filesystem;

int hexDigit(char c)
{
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

std::vector<unsigned char> decodeHex(const std::string& hex)
{
    std::vector<unsigned char> bytes(hex.size() / 2);
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        const int high = hexDigit(hex[2 * i]), low = hexDigit(hex[2 * i + 1]);
        if (high < 0 || low < 0)
            throw InputError("grey",
                             "character " + std::to_string(2 * i) + " is not a hexadecimal digit");
        bytes[i] = static_cast<unsigned char>(high * 16 + low);
    }
    return bytes;
}

/// Creates the first <node>.<k>.png that does not exist yet (O_EXCL: never one that does).
fs::path reserveName(const fs::path& dir, const std::string& node)
{
    for (int k = 1; k < 100000; ++k) {
        const fs::path file = dir / (node + "." + std::to_string(k) + ".png");
        const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
        if (fd >= 0) {
            ::close(fd);
            return file;
        }
        if (errno != EEXIST)
            throw InputError(file.string(), std::string("cannot create: ") + std::strerror(errno));
    }
    throw InputError(dir.string(), "no free name for a painting of '" + node + "'");
}

}  // namespace

fs::path writePaintedMap(const fs::path& outDir, const std::string& node, long width, long height,
                         const std::string& hex)
{
    if (width < 1 || height < 1 || width > kMaxPaintedPixels || height > kMaxPaintedPixels)
        throw InputError("width", "a painting is 1 to " + std::to_string(kMaxPaintedPixels) +
                                      " pixels a side, got " + std::to_string(width) + " x " +
                                      std::to_string(height));
    if (width * height > kMaxPaintedPixels)
        throw InputError("width", "a painting has at most " + std::to_string(kMaxPaintedPixels) +
                                      " pixels, got " + std::to_string(width * height));
    const auto pixels = static_cast<std::size_t>(width * height);
    if (hex.size() != 2 * pixels)
        throw InputError("grey", "needs " + std::to_string(2 * pixels) +
                                     " hexadecimal digits (two a pixel), got " +
                                     std::to_string(hex.size()));
    const std::vector<unsigned char> grey = decodeHex(hex);
    std::vector<const unsigned char*> rows(static_cast<std::size_t>(height));
    for (std::size_t y = 0; y < rows.size(); ++y)
        rows[y] = grey.data() + y * static_cast<std::size_t>(width);

    const fs::path dir = outDir / "paintings";
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw InputError(dir.string(), "cannot create: " + ec.message());
    const fs::path file = reserveName(dir, node);
    try {
        formats::writePng(file.string(), static_cast<int>(width), static_cast<int>(height), 1, 8,
                          rows, /*srgb=*/false);
    } catch (const std::exception& e) {
        fs::remove(file, ec);
        throw InputError(file.string(), e.what());
    }
    return file;
}

}  // namespace cg::cli
