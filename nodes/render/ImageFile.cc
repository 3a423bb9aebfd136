#include "nodes/render/ImageFile.h"

#include <cstdint>
#include <stdexcept>
#include <vector>

#include "algo/render/image/CloudLayer.h"
#include "formats/ExrFile.h"
#include "formats/PngFile.h"
#include "nodes/data/Image.h"
#include "util/AtomicFile.h"

namespace cg {

namespace {

bool endsWith(const std::string& s, const std::string& tail)
{
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

/// The beauty as R, G, B, A (what a reader of the default layer sees) and, where the image has
/// a background, the layers "cloud" (premultiplied, background excluded) and "background".
void writeExr(const std::string& path, const ImageData& image)
{
    if (!image.hasBackground()) {
        formats::writeExrRgba32(path, image.width, image.height, image.rgba);
        return;
    }
    const std::vector<float> cloud = algo::cloudLayer(image.rgba, image.background);
    formats::writeExrFloat32(
        path, image.width, image.height,
        {{{"R", "G", "B", "A"}, image.rgba},
         {{"cloud.R", "cloud.G", "cloud.B", "cloud.A"}, cloud},
         {{"background.R", "background.G", "background.B"}, image.background}});
}

}  // namespace

bool isImageFileName(const std::string& file)
{
    return endsWith(file, ".png") || endsWith(file, ".exr");
}

void writeImageFile(const std::filesystem::path& path, const ImageData& image,
                    const algo::DisplaySettings& display)
{
    const std::string name = path.string();
    if (!isImageFileName(name))
        throw std::invalid_argument("'" + name +
                                    "' must end in .png (8-bit sRGB) or .exr (linear float)");
    util::AtomicOutput out(path);
    if (endsWith(name, ".exr")) {
        writeExr(out.tempPath().string(), image);
    } else {
        const std::vector<std::uint8_t> rgb =
            algo::displayRgb8(image.rgba, image.width, image.height, display);
        formats::writePngRgb8(out.tempPath().string(), image.width, image.height, rgb);
    }
    out.commit();
}

}  // namespace cg
