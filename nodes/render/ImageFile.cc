#include "nodes/render/ImageFile.h"

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <vector>

#include "algo/render/CameraMatrices.h"
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

formats::ExrMatrix toExr(const algo::Matrix44& m)
{
    formats::ExrMatrix out{};
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) out[r][c] = static_cast<float>(m[r][c]);
    return out;
}

/// OpenEXR's worldToCamera and worldToNDC of the camera the image was rendered with.
std::optional<formats::ExrCamera> exrCamera(const ImageData& image)
{
    if (!image.camera) return std::nullopt;
    return formats::ExrCamera{toExr(algo::worldToCamera(*image.camera)),
                              toExr(algo::worldToNdc(*image.camera))};
}

/// The beauty as R, G, B, A (what a reader of the default layer sees) and, where the image has
/// a background, the layers "cloud" (premultiplied, background excluded) and "background";
/// where it has AOVs, "sun" and "sky" (the cloud's light by where it comes from: their sum is
/// the cloud layer's RGB), "depth" (Z) and "shadow" (A, the ground's shadow matte); the
/// camera's matrices where the image has one.
void writeExr(const std::string& path, const ImageData& image)
{
    std::vector<formats::ExrPixels> parts = {{{"R", "G", "B", "A"}, image.rgba}};
    std::vector<float> cloud;
    if (image.hasBackground()) {
        cloud = algo::cloudLayer(image.rgba, image.background);
        parts.push_back({{"cloud.R", "cloud.G", "cloud.B", "cloud.A"}, cloud});
        parts.push_back({{"background.R", "background.G", "background.B"}, image.background});
    }
    if (!image.aovs.empty()) {
        parts.push_back({{"sun.R", "sun.G", "sun.B"}, image.aovs.sun});
        parts.push_back({{"sky.R", "sky.G", "sky.B"}, image.aovs.sky});
        parts.push_back({{"depth.Z"}, image.aovs.depth});
        parts.push_back({{"shadow.A"}, image.aovs.shadow});
    }
    formats::writeExrFloat32(path, image.width, image.height, parts, exrCamera(image));
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
