#include "formats/MapImage.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>

#include "formats/PngFile.h"

namespace cg::formats {

namespace {

void checkSize(const char* what, int nx, int ny, const std::vector<float>& values)
{
    if (nx < 1 || ny < 1 ||
        values.size() != static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny)) {
        throw std::invalid_argument(std::string(what) + ": " + std::to_string(values.size()) +
                                    " values do not make a " + std::to_string(nx) + " x " +
                                    std::to_string(ny) + " map");
    }
}

[[noreturn]] void malformed(const std::string& path, const std::string& why)
{
    throw std::runtime_error(path + ": not a valid greyscale PFM: " + why);
}

}  // namespace

void writePfm(const std::string& path, int nx, int ny, const std::vector<float>& values)
{
    checkSize("writePfm", nx, ny, values);
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(path + ": cannot open for writing");
    out << "Pf\n" << nx << ' ' << ny << "\n-1.0\n";  // negative scale: little-endian

    const auto w = static_cast<std::size_t>(nx);
    std::vector<unsigned char> row(w * 4);
    // PFM rows run bottom to top and our row iy = 0 is the bottom, so rows go out in order.
    for (std::size_t iy = 0; iy < static_cast<std::size_t>(ny); ++iy) {
        for (std::size_t ix = 0; ix < w; ++ix) {
            std::uint32_t bits;
            std::memcpy(&bits, &values[iy * w + ix], 4);
            for (int b = 0; b < 4; ++b)
                row[ix * 4 + static_cast<std::size_t>(b)] =
                    static_cast<unsigned char>(bits >> (8 * b));
        }
        out.write(reinterpret_cast<const char*>(row.data()),
                  static_cast<std::streamsize>(row.size()));
    }
    out.close();
    if (!out) throw std::runtime_error(path + ": write failed");
}

MapImage readPfm(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot open for reading");
    const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw std::runtime_error(path + ": read failed");

    // Header: three whitespace-separated tokens after the magic, then one whitespace byte.
    std::size_t pos = 0;
    const auto isSpace = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
    const auto token = [&](const char* what) {
        while (pos < data.size() && isSpace(data[pos])) ++pos;
        const std::size_t start = pos;
        while (pos < data.size() && !isSpace(data[pos])) ++pos;
        if (start == pos || pos - start > 32) malformed(path, std::string("bad ") + what);
        return data.substr(start, pos - start);
    };
    if (data.size() < 2 || data[0] != 'P') malformed(path, "no PFM magic");
    if (data[1] == 'F') malformed(path, "colour PFM (PF); expected greyscale (Pf)");
    if (data[1] != 'f' || data.size() < 3 || !isSpace(data[2])) malformed(path, "no Pf magic");
    pos = 2;

    const auto parseInt = [&](const std::string& t, const char* what) {
        if (t.find_first_not_of("0123456789") != std::string::npos)
            malformed(path, std::string("bad ") + what + " '" + t + "'");
        const long long v = std::strtoll(t.c_str(), nullptr, 10);
        if (v < 1 || v > std::numeric_limits<int>::max())
            malformed(path, std::string(what) + " " + t + " out of range");
        return static_cast<int>(v);
    };
    const int nx = parseInt(token("width"), "width");
    const int ny = parseInt(token("height"), "height");
    const std::string scaleText = token("scale");
    char* end = nullptr;
    errno = 0;
    const double scale = std::strtod(scaleText.c_str(), &end);
    if (errno != 0 || end != scaleText.c_str() + scaleText.size() || !std::isfinite(scale) ||
        scale == 0.0) {
        malformed(path, "bad scale '" + scaleText + "'");
    }
    if (pos >= data.size() || !isSpace(data[pos])) malformed(path, "header not terminated");
    ++pos;

    const std::uint64_t count = static_cast<std::uint64_t>(nx) * static_cast<std::uint64_t>(ny);
    const std::uint64_t have = data.size() - pos;
    if (have != count * 4) {
        malformed(path, std::to_string(nx) + " x " + std::to_string(ny) + " needs " +
                            std::to_string(count * 4) + " data bytes, found " +
                            std::to_string(have));
    }

    const bool littleEndian = scale < 0.0;
    MapImage img;
    img.nx = nx;
    img.ny = ny;
    img.values.resize(static_cast<std::size_t>(count));
    const auto* bytes = reinterpret_cast<const unsigned char*>(data.data() + pos);
    for (std::size_t i = 0; i < img.values.size(); ++i) {
        std::uint32_t bits = 0;
        for (int b = 0; b < 4; ++b) {
            const unsigned shift = littleEndian ? 8u * unsigned(b) : 8u * unsigned(3 - b);
            bits |= std::uint32_t(bytes[i * 4 + static_cast<std::size_t>(b)]) << shift;
        }
        std::memcpy(&img.values[i], &bits, 4);
    }
    return img;
}

void writePng16(const std::string& path, int nx, int ny, const std::vector<float>& values)
{
    checkSize("writePng16", nx, ny, values);
    const auto w = static_cast<std::size_t>(nx);
    const auto h = static_cast<std::size_t>(ny);
    std::vector<unsigned char> pixels(w * h * 2);
    std::vector<const unsigned char*> rows(h);
    for (std::size_t r = 0; r < h; ++r) {
        // PNG rows run top to bottom; the top row is our iy = ny - 1.
        const std::size_t iy = h - 1 - r;
        unsigned char* row = pixels.data() + r * w * 2;
        rows[r] = row;
        for (std::size_t ix = 0; ix < w; ++ix) {
            const float v = values[iy * w + ix];
            const float c = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
            const auto q = static_cast<std::uint16_t>(std::lround(double(c) * 65535.0));
            row[ix * 2] = static_cast<unsigned char>(q >> 8);  // PNG samples are big-endian
            row[ix * 2 + 1] = static_cast<unsigned char>(q & 0xff);
        }
    }
    writePng(path, nx, ny, 1, 16, rows, /*srgb=*/false);
}

MapImage readPng16(const std::string& path)
{
    const PngPixels px = readPng(path, 1, 16, 1u << 20);
    const auto w = static_cast<std::size_t>(px.width);
    const auto h = static_cast<std::size_t>(px.height);
    MapImage img;
    img.nx = px.width;
    img.ny = px.height;
    img.values.resize(w * h);
    for (std::size_t r = 0; r < h; ++r) {
        const unsigned char* row = px.bytes.data() + r * w * 2;
        const std::size_t iy = h - 1 - r;
        for (std::size_t ix = 0; ix < w; ++ix) {
            const unsigned q = (unsigned(row[ix * 2]) << 8) | row[ix * 2 + 1];
            img.values[iy * w + ix] = static_cast<float>(q / 65535.0);
        }
    }
    return img;
}

}  // namespace cg::formats
