#include "nodes/algo/MapImage.h"

#include <png.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>

namespace cg::algo {

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

// ---------------------------------------------------------------------------------------
// libpng reports errors by longjmp. Each function that calls libpng sets its own jump
// target and holds no C++ object whose destructor a jump could skip; errors are copied into
// PngError and thrown as exceptions by the C++ caller.

struct PngError {
    char message[256] = "";
};

void pngErrorFn(png_structp png, png_const_charp msg)
{
    auto* err = static_cast<PngError*>(png_get_error_ptr(png));
    std::snprintf(err->message, sizeof err->message, "%s", msg ? msg : "libpng error");
    png_longjmp(png, 1);
}

void pngWarningFn(png_structp, png_const_charp) {}  // warnings are not failures

bool pngWrite(png_structp png, png_infop info, std::FILE* file, int nx, int ny, png_bytepp rows)
{
    if (setjmp(png_jmpbuf(png))) return false;
    png_init_io(png, file);
    png_set_IHDR(png, info, static_cast<png_uint_32>(nx), static_cast<png_uint_32>(ny), 16,
                 PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    png_write_image(png, rows);  // samples are already big-endian, as PNG stores them
    png_write_end(png, nullptr);
    return true;
}

struct PngHeader {
    png_uint_32 width = 0;
    png_uint_32 height = 0;
    int bitDepth = 0;
    int colorType = 0;
};

bool pngReadHeader(png_structp png, png_infop info, std::FILE* file, PngHeader* h)
{
    if (setjmp(png_jmpbuf(png))) return false;
    png_init_io(png, file);
    png_set_user_limits(png, 1u << 20, 1u << 20);
    png_read_info(png, info);
    h->width = png_get_image_width(png, info);
    h->height = png_get_image_height(png, info);
    h->bitDepth = png_get_bit_depth(png, info);
    h->colorType = png_get_color_type(png, info);
    return true;
}

bool pngReadRows(png_structp png, png_infop info, png_bytepp rows)
{
    if (setjmp(png_jmpbuf(png))) return false;
    png_read_image(png, rows);
    png_read_end(png, info);
    return true;
}

struct File {
    std::FILE* f = nullptr;
    ~File()
    {
        if (f) std::fclose(f);
    }
};

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
    std::vector<png_byte> pixels(w * h * 2);
    std::vector<png_bytep> rows(h);
    for (std::size_t r = 0; r < h; ++r) {
        // PNG rows run top to bottom; the top row is our iy = ny - 1.
        const std::size_t iy = h - 1 - r;
        rows[r] = pixels.data() + r * w * 2;
        for (std::size_t ix = 0; ix < w; ++ix) {
            const float v = values[iy * w + ix];
            const float c = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
            const auto q = static_cast<std::uint16_t>(std::lround(double(c) * 65535.0));
            rows[r][ix * 2] = static_cast<png_byte>(q >> 8);
            rows[r][ix * 2 + 1] = static_cast<png_byte>(q & 0xff);
        }
    }

    File file;
    file.f = std::fopen(path.c_str(), "wb");
    if (!file.f) throw std::runtime_error(path + ": cannot open for writing");
    PngError err;
    png_structp png =
        png_create_write_struct(PNG_LIBPNG_VER_STRING, &err, pngErrorFn, pngWarningFn);
    if (!png) throw std::runtime_error(path + ": libpng could not start");
    png_infop info = png_create_info_struct(png);
    if (!info) {
        png_destroy_write_struct(&png, nullptr);
        throw std::runtime_error(path + ": libpng could not start");
    }
    const bool ok = pngWrite(png, info, file.f, nx, ny, rows.data());
    png_destroy_write_struct(&png, &info);
    if (!ok) throw std::runtime_error(path + ": PNG write failed: " + err.message);
    const bool flushed = std::fflush(file.f) == 0 && !std::ferror(file.f);
    const bool closed = std::fclose(file.f) == 0;
    file.f = nullptr;
    if (!flushed || !closed) throw std::runtime_error(path + ": write failed");
}

MapImage readPng16(const std::string& path)
{
    File file;
    file.f = std::fopen(path.c_str(), "rb");
    if (!file.f) throw std::runtime_error(path + ": cannot open for reading");
    png_byte sig[8];
    if (std::fread(sig, 1, 8, file.f) != 8 || png_sig_cmp(sig, 0, 8) != 0)
        throw std::runtime_error(path + ": not a PNG file");
    std::rewind(file.f);

    PngError err;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &err, pngErrorFn, pngWarningFn);
    if (!png) throw std::runtime_error(path + ": libpng could not start");
    png_infop info = png_create_info_struct(png);
    if (!info) {
        png_destroy_read_struct(&png, nullptr, nullptr);
        throw std::runtime_error(path + ": libpng could not start");
    }
    struct ReadGuard {
        png_structp* png;
        png_infop* info;
        ~ReadGuard() { png_destroy_read_struct(png, info, nullptr); }
    } guard{&png, &info};

    PngHeader hdr;
    if (!pngReadHeader(png, info, file.f, &hdr))
        throw std::runtime_error(path + ": PNG read failed: " + err.message);
    if (hdr.bitDepth != 16 || hdr.colorType != PNG_COLOR_TYPE_GRAY)
        throw std::runtime_error(path + ": not a 16-bit greyscale PNG");

    const std::size_t w = hdr.width;
    const std::size_t h = hdr.height;
    std::vector<png_byte> pixels(w * h * 2);
    std::vector<png_bytep> rows(h);
    for (std::size_t r = 0; r < h; ++r) rows[r] = pixels.data() + r * w * 2;
    if (!pngReadRows(png, info, rows.data()))
        throw std::runtime_error(path + ": PNG read failed: " + err.message);

    MapImage img;
    img.nx = static_cast<int>(w);
    img.ny = static_cast<int>(h);
    img.values.resize(w * h);
    for (std::size_t r = 0; r < h; ++r) {
        const std::size_t iy = h - 1 - r;
        for (std::size_t ix = 0; ix < w; ++ix) {
            const unsigned q = (unsigned(rows[r][ix * 2]) << 8) | rows[r][ix * 2 + 1];
            img.values[iy * w + ix] = static_cast<float>(q / 65535.0);
        }
    }
    return img;
}

}  // namespace cg::algo
