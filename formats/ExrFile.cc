#include "formats/ExrFile.h"

#include <cstddef>
#include <stdexcept>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>

namespace cg::formats {

namespace {

constexpr const char* kChannels[4] = {"R", "G", "B", "A"};

/// A frame buffer over interleaved RGBA floats, top row first: channel c of pixel (x, y) is
/// base[4 (y w + x) + c], as OpenEXR's data window (0,0)-(w-1,h-1) addresses it.
Imf::FrameBuffer rgbaSlices(float* base, int width, bool fillMissing)
{
    Imf::FrameBuffer fb;
    const std::size_t xStride = 4 * sizeof(float);
    const std::size_t yStride = xStride * static_cast<std::size_t>(width);
    for (int c = 0; c < 4; ++c)
        fb.insert(kChannels[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(base + c), xStride,
                                           yStride, 1, 1, fillMissing && c == 3 ? 1.0 : 0.0));
    return fb;
}

}  // namespace

void writeExrRgba32(const std::string& path, int width, int height, const std::vector<float>& rgba)
{
    if (width <= 0 || height <= 0 ||
        rgba.size() != 4 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
        throw std::invalid_argument("writeExrRgba32: image size does not match its pixels");
    try {
        Imf::Header header(width, height);
        header.compression() = Imf::ZIP_COMPRESSION;
        for (const char* c : kChannels) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
        Imf::OutputFile file(path.c_str(), header);
        // OpenEXR only reads through the frame buffer; its API takes a non-const pointer.
        file.setFrameBuffer(rgbaSlices(const_cast<float*>(rgba.data()), width, false));
        file.writePixels(height);
    } catch (const std::exception& e) {
        throw std::runtime_error(path + ": cannot write OpenEXR: " + e.what());
    }
}

ExrRgbaImage readExrRgba(const std::string& path)
{
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i dw = file.header().dataWindow();
        ExrRgbaImage out;
        out.width = dw.max.x - dw.min.x + 1;
        out.height = dw.max.y - dw.min.y + 1;
        if (dw.min.x != 0 || dw.min.y != 0 || out.width <= 0 || out.height <= 0 ||
            out.width > (1 << 16) || out.height > (1 << 16))
            throw std::runtime_error("unsupported data window");
        out.rgba.resize(4 * static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height));
        file.setFrameBuffer(rgbaSlices(out.rgba.data(), out.width, true));
        file.readPixels(dw.min.y, dw.max.y);
        return out;
    } catch (const std::exception& e) {
        throw std::runtime_error(path + ": cannot read OpenEXR: " + e.what());
    }
}

}  // namespace cg::formats
