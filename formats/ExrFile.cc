#include "formats/ExrFile.h"

#include <cstddef>
#include <set>
#include <stdexcept>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStandardAttributes.h>

namespace cg::formats {

namespace {

/// Adds the slices of `count` interleaved float channels to `fb`: channel c of pixel (x, y) is
/// base[count (y w + x) + c], as OpenEXR's data window (0,0)-(w-1,h-1) addresses it. A channel
/// missing from the file reads as fill(name).
template <class Fill>
void insertSlices(Imf::FrameBuffer& fb, float* base, int width,
                  const std::vector<std::string>& channels, Fill fill)
{
    const std::size_t count = channels.size();
    const std::size_t xStride = count * sizeof(float);
    const std::size_t yStride = xStride * static_cast<std::size_t>(width);
    for (std::size_t c = 0; c < count; ++c)
        fb.insert(channels[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(base + c), xStride,
                                          yStride, 1, 1, fill(channels[c])));
}

const std::vector<std::string>& rgbaNames()
{
    static const std::vector<std::string> names = {"R", "G", "B", "A"};
    return names;
}

/// The data window of a file we can read: from (0, 0), at most 65536 pixels a side.
void checkedSize(const Imf::Header& header, int& width, int& height)
{
    const Imath::Box2i& dw = header.dataWindow();
    width = dw.max.x - dw.min.x + 1;
    height = dw.max.y - dw.min.y + 1;
    if (dw.min.x != 0 || dw.min.y != 0 || width <= 0 || height <= 0 || width > (1 << 16) ||
        height > (1 << 16))
        throw std::runtime_error("unsupported data window");
}

Imath::M44f toImath(const ExrMatrix& m)
{
    Imath::M44f out;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) out[r][c] = m[r][c];
    return out;
}

ExrMatrix fromImath(const Imath::M44f& m)
{
    ExrMatrix out{};
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) out[r][c] = m[r][c];
    return out;
}

}  // namespace

ExrChannelImage readExrLuminance(const std::string& path, std::uint64_t maxPixels)
{
    try {
        Imf::InputFile file(path.c_str());
        ExrChannelImage out;
        checkedSize(file.header(), out.width, out.height);
        const std::uint64_t pixels =
            static_cast<std::uint64_t>(out.width) * static_cast<std::uint64_t>(out.height);
        if (pixels > maxPixels)
            throw std::runtime_error(std::to_string(out.width) + " x " +
                                     std::to_string(out.height) + " pixels are more than " +
                                     std::to_string(maxPixels));
        const Imf::ChannelList& list = file.header().channels();
        const bool hasY = list.findChannel("Y") != nullptr;
        if (!hasY && !list.findChannel("R") && !list.findChannel("G") && !list.findChannel("B"))
            throw std::runtime_error("no Y, R, G or B channel");
        // A channel the file lacks reads as the slice's fill, 0.
        const std::vector<std::string> read =
            hasY ? std::vector<std::string>{"Y"} : std::vector<std::string>{"R", "G", "B"};
        std::vector<float> values(read.size() * static_cast<std::size_t>(pixels));
        Imf::FrameBuffer fb;
        insertSlices(fb, values.data(), out.width, read, [](const std::string&) { return 0.0; });
        file.setFrameBuffer(fb);
        file.readPixels(0, out.height - 1);
        out.channels = {"Y"};
        if (hasY) {
            out.values = std::move(values);
            return out;
        }
        out.values.resize(static_cast<std::size_t>(pixels));
        for (std::size_t i = 0; i < out.values.size(); ++i)
            out.values[i] =
                0.2126f * values[3 * i] + 0.7152f * values[3 * i + 1] + 0.0722f * values[3 * i + 2];
        return out;
    } catch (const std::exception& e) {
        throw std::runtime_error(path + ": cannot read OpenEXR: " + e.what());
    }
}

std::optional<ExrCamera> readExrCamera(const std::string& path)
{
    try {
        Imf::InputFile file(path.c_str());
        const Imf::Header& h = file.header();
        if (!Imf::hasWorldToCamera(h) || !Imf::hasWorldToNDC(h)) return std::nullopt;
        return ExrCamera{fromImath(Imf::worldToCamera(h)), fromImath(Imf::worldToNDC(h))};
    } catch (const std::exception& e) {
        throw std::runtime_error(path + ": cannot read OpenEXR: " + e.what());
    }
}

std::optional<ExrChromaticities> readExrChromaticities(const std::string& path)
{
    try {
        Imf::InputFile file(path.c_str());
        if (!Imf::hasChromaticities(file.header())) return std::nullopt;
        const Imf::Chromaticities c = Imf::chromaticities(file.header());
        return ExrChromaticities{c.red.x,  c.red.y,  c.green.x, c.green.y,
                                 c.blue.x, c.blue.y, c.white.x, c.white.y};
    } catch (const std::exception& e) {
        throw std::runtime_error(path + ": cannot read OpenEXR: " + e.what());
    }
}

void writeExrFloat32(const std::string& path, int width, int height,
                     const std::vector<ExrPixels>& parts, const std::optional<ExrCamera>& camera)
{
    const std::size_t pixels =
        width > 0 && height > 0 ? static_cast<std::size_t>(width) * static_cast<std::size_t>(height)
                                : 0;
    std::set<std::string> names;
    for (const ExrPixels& part : parts) {
        if (pixels == 0 || part.channels.empty() ||
            part.values.size() != part.channels.size() * pixels)
            throw std::invalid_argument("writeExrFloat32: image size does not match its pixels");
        for (const std::string& name : part.channels)
            if (name.empty() || !names.insert(name).second)
                throw std::invalid_argument("writeExrFloat32: channel name '" + name +
                                            "' is empty or repeated");
    }
    try {
        Imf::Header header(width, height);
        header.compression() = Imf::ZIP_COMPRESSION;
        // The renderer works in linear Rec.709 / sRGB primaries, D65 white: OpenEXR's default
        // chromaticities, written out so that a colour-managed reader need not assume them.
        Imf::addChromaticities(header, Imf::Chromaticities());
        if (camera) {
            Imf::addWorldToCamera(header, toImath(camera->worldToCamera));
            Imf::addWorldToNDC(header, toImath(camera->worldToNDC));
        }
        for (const std::string& name : names)
            header.channels().insert(name, Imf::Channel(Imf::FLOAT));
        Imf::OutputFile file(path.c_str(), header);
        Imf::FrameBuffer fb;
        // OpenEXR only reads through the frame buffer; its API takes a non-const pointer.
        for (const ExrPixels& part : parts)
            insertSlices(fb, const_cast<float*>(part.values.data()), width, part.channels,
                         [](const std::string&) { return 0.0; });
        file.setFrameBuffer(fb);
        file.writePixels(height);
    } catch (const std::exception& e) {
        throw std::runtime_error(path + ": cannot write OpenEXR: " + e.what());
    }
}

void writeExrRgba32(const std::string& path, int width, int height, const std::vector<float>& rgba)
{
    if (width <= 0 || height <= 0 ||
        rgba.size() != 4 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
        throw std::invalid_argument("writeExrRgba32: image size does not match its pixels");
    writeExrFloat32(path, width, height, {{rgbaNames(), rgba}});
}

ExrRgbaImage readExrRgba(const std::string& path)
{
    try {
        Imf::InputFile file(path.c_str());
        ExrRgbaImage out;
        checkedSize(file.header(), out.width, out.height);
        out.rgba.resize(4 * static_cast<std::size_t>(out.width) *
                        static_cast<std::size_t>(out.height));
        Imf::FrameBuffer fb;
        insertSlices(fb, out.rgba.data(), out.width, rgbaNames(),
                     [](const std::string& name) { return name == "A" ? 1.0 : 0.0; });
        file.setFrameBuffer(fb);
        file.readPixels(0, out.height - 1);
        return out;
    } catch (const std::exception& e) {
        throw std::runtime_error(path + ": cannot read OpenEXR: " + e.what());
    }
}

ExrChannelImage readExrChannels(const std::string& path, const std::vector<std::string>& channels)
{
    try {
        Imf::InputFile file(path.c_str());
        ExrChannelImage out;
        checkedSize(file.header(), out.width, out.height);
        for (const std::string& name : channels)
            if (!file.header().channels().findChannel(name))
                throw std::runtime_error("no channel '" + name + "'");
        out.channels = channels;
        out.values.resize(channels.size() * static_cast<std::size_t>(out.width) *
                          static_cast<std::size_t>(out.height));
        if (channels.empty()) return out;
        Imf::FrameBuffer fb;
        insertSlices(fb, out.values.data(), out.width, channels,
                     [](const std::string&) { return 0.0; });
        file.setFrameBuffer(fb);
        file.readPixels(0, out.height - 1);
        return out;
    } catch (const std::exception& e) {
        throw std::runtime_error(path + ": cannot read OpenEXR: " + e.what());
    }
}

std::vector<std::string> exrChannelNames(const std::string& path)
{
    try {
        Imf::InputFile file(path.c_str());
        std::vector<std::string> names;
        const Imf::ChannelList& list = file.header().channels();
        for (auto it = list.begin(); it != list.end(); ++it) names.emplace_back(it.name());
        return names;
    } catch (const std::exception& e) {
        throw std::runtime_error(path + ": cannot read OpenEXR: " + e.what());
    }
}

}  // namespace cg::formats
