#include "formats/PngFile.h"

#include <png.h>

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <utility>

namespace cg::formats {

namespace {

// ---------------------------------------------------------------------------------------
// libpng reports errors by longjmp. Each function below that calls libpng sets its own jump
// target and holds no C++ object whose destructor a jump could skip; the error text is copied
// into PngError and thrown as an exception by the C++ caller.

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

int colorType(int channels) { return channels == 1 ? PNG_COLOR_TYPE_GRAY : PNG_COLOR_TYPE_RGB; }

std::string formatName(int channels, int bitDepth)
{
    return std::string(bitDepth == 8 ? "an 8" : "a " + std::to_string(bitDepth)) + "-bit " +
           (channels == 1 ? "greyscale" : "RGB");
}

bool pngWrite(png_structp png, png_infop info, std::FILE* file, int w, int h, int channels,
              int bitDepth, bool srgb, png_bytepp rows)
{
    if (setjmp(png_jmpbuf(png))) return false;
    png_init_io(png, file);
    png_set_IHDR(png, info, static_cast<png_uint_32>(w), static_cast<png_uint_32>(h), bitDepth,
                 colorType(channels), PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    if (srgb) png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    // Fast deflate: dithered renders barely compress, and at the default level 6 the encoder
    // cost about as much as rendering a small frame; level 2 files are a few percent larger.
    png_set_compression_level(png, 2);
    png_write_info(png, info);
    png_write_image(png, rows);
    png_write_end(png, nullptr);
    return true;
}

struct PngHeader {
    png_uint_32 width = 0;
    png_uint_32 height = 0;
    int bitDepth = 0;
    int colorType = 0;
};

bool pngReadHeader(png_structp png, png_infop info, std::FILE* file, png_uint_32 maxSide,
                   PngHeader* h)
{
    if (setjmp(png_jmpbuf(png))) return false;
    png_init_io(png, file);
    png_set_user_limits(png, maxSide, maxSide);
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
    png_read_image(png, rows);  // de-interlaces if the file is interlaced
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

namespace {

/// Writes the PNG into `f` and closes it; `name` says where in messages.
void writePngStream(std::FILE* f, const std::string& name, int width, int height, int channels,
                    int bitDepth, const std::vector<const unsigned char*>& rows, bool srgb)
{
    File file;
    file.f = f;
    PngError err;
    png_structp png =
        png_create_write_struct(PNG_LIBPNG_VER_STRING, &err, pngErrorFn, pngWarningFn);
    if (!png) throw std::runtime_error(name + ": libpng could not start");
    png_infop info = png_create_info_struct(png);
    if (!info) {
        png_destroy_write_struct(&png, nullptr);
        throw std::runtime_error(name + ": libpng could not start");
    }
    // png_write_image takes non-const rows but only reads them.
    const bool ok = pngWrite(png, info, file.f, width, height, channels, bitDepth, srgb,
                             const_cast<png_bytepp>(rows.data()));
    png_destroy_write_struct(&png, &info);
    if (!ok) throw std::runtime_error(name + ": PNG write failed: " + err.message);
    // Close explicitly: a failed flush (e.g. disk full) must not pass as success.
    const bool flushed = std::fflush(file.f) == 0 && !std::ferror(file.f);
    const bool closed = std::fclose(file.f) == 0;
    file.f = nullptr;
    if (!flushed || !closed) throw std::runtime_error(name + ": write failed");
}

void checkWritable(int width, int height, int channels, int bitDepth, std::size_t rows)
{
    if (width < 1 || height < 1 || rows != static_cast<std::size_t>(height) ||
        (channels != 1 && channels != 3) || (bitDepth != 8 && bitDepth != 16))
        throw std::invalid_argument("writePng: bad image size or format");
}

std::vector<const unsigned char*> rgb8Rows(int width, int height,
                                           const std::vector<std::uint8_t>& rgb)
{
    if (width < 1 || height < 1 ||
        rgb.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3)
        throw std::invalid_argument("writePngRgb8: bad image size");
    const auto w = static_cast<std::size_t>(width);
    std::vector<const unsigned char*> rows(static_cast<std::size_t>(height));
    for (std::size_t r = 0; r < rows.size(); ++r) rows[r] = rgb.data() + r * w * 3;
    return rows;
}

}  // namespace

void writePng(const std::string& path, int width, int height, int channels, int bitDepth,
              const std::vector<const unsigned char*>& rows, bool srgb)
{
    checkWritable(width, height, channels, bitDepth, rows.size());
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) throw std::runtime_error(path + ": cannot open for writing");
    writePngStream(f, path, width, height, channels, bitDepth, rows, srgb);
}

PngPixels readPng(const std::string& path, int channels, int bitDepth, std::uint32_t maxSide)
{
    if ((channels != 0 && channels != 1 && channels != 3) ||
        (bitDepth != 0 && bitDepth != 8 && bitDepth != 16))
        throw std::invalid_argument("readPng: bad format");
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
    if (!pngReadHeader(png, info, file.f, maxSide, &hdr))
        throw std::runtime_error(path + ": PNG read failed: " + err.message);
    // Checked before the pixels are read, so a wrong format is reported as such even when
    // the data would also be bad.
    const int storedChannels = hdr.colorType == PNG_COLOR_TYPE_GRAY  ? 1
                               : hdr.colorType == PNG_COLOR_TYPE_RGB ? 3
                                                                     : 0;
    const bool depthOk =
        bitDepth == 0 ? hdr.bitDepth == 8 || hdr.bitDepth == 16 : hdr.bitDepth == bitDepth;
    const bool typeOk = channels == 0 ? storedChannels != 0 : hdr.colorType == colorType(channels);
    if (!depthOk || !typeOk)
        throw std::runtime_error(
            path + ": not " +
            (channels == 0 || bitDepth == 0
                 ? std::string("a greyscale or RGB PNG of 8 or 16 bits (flatten an alpha "
                               "channel, convert a palette)")
                 : formatName(channels, bitDepth) + " PNG"));
    channels = storedChannels;
    bitDepth = hdr.bitDepth;

    PngPixels px;
    px.width = static_cast<int>(hdr.width);
    px.height = static_cast<int>(hdr.height);
    px.channels = channels;
    px.bitDepth = bitDepth;
    const std::size_t rowBytes =
        std::size_t(hdr.width) * static_cast<std::size_t>(channels * bitDepth / 8);
    px.bytes.resize(rowBytes * hdr.height);
    std::vector<png_bytep> rows(hdr.height);
    for (std::size_t r = 0; r < rows.size(); ++r) rows[r] = px.bytes.data() + r * rowBytes;
    if (!pngReadRows(png, info, rows.data()))
        throw std::runtime_error(path + ": PNG read failed: " + err.message);
    return px;
}

void writePngRgb8(const std::string& path, int width, int height,
                  const std::vector<std::uint8_t>& rgb)
{
    writePng(path, width, height, 3, 8, rgb8Rows(width, height, rgb), /*srgb=*/true);
}

std::string encodePngRgb8(int width, int height, const std::vector<std::uint8_t>& rgb)
{
    const std::vector<const unsigned char*> rows = rgb8Rows(width, height, rgb);
    char* bytes = nullptr;
    std::size_t size = 0;
    std::FILE* f = ::open_memstream(&bytes, &size);
    if (!f) throw std::runtime_error("PNG in memory: cannot open a memory stream");
    std::string png;
    try {
        writePngStream(f, "PNG in memory", width, height, 3, 8, rows, /*srgb=*/true);
        png.assign(bytes, size);
    } catch (...) {
        std::free(bytes);
        throw;
    }
    std::free(bytes);
    return png;
}

Rgb8Image readPngRgb8(const std::string& path)
{
    PngPixels px = readPng(path, 3, 8, 1u << 16);
    Rgb8Image img;
    img.width = px.width;
    img.height = px.height;
    img.rgb = std::move(px.bytes);
    return img;
}

}  // namespace cg::formats
