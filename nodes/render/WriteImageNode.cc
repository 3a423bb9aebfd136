// WriteImage: a linear radiance image to an 8-bit sRGB PNG (exposure, filmic tone map) or to a
// linear OpenEXR file, chosen by the file's extension; an image with a background becomes a
// multi-layer EXR (beauty, cloud, background).

#include <filesystem>
#include <memory>
#include <string>

#include "algo/render/CloudLayer.h"
#include "algo/render/Display.h"
#include "core/CoreData.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "formats/ExrFile.h"
#include "formats/PngFile.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/Image.h"
#include "nodes/io/WriterSupport.h"
#include "nodes/render/RenderNodes.h"
#include "util/AtomicFile.h"

namespace cg {

namespace {

bool endsWith(const std::string& s, const std::string& tail)
{
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

bool isExr(const std::string& file) { return endsWith(file, ".exr"); }

/// The beauty as R, G, B, A (what a reader of the default layer sees) and, where the image has
/// a background, the layers "cloud" (premultiplied, background excluded) and "background".
void writeExr(const std::string& path, const ImageData& image)
{
    if (!image.hasBackground()) {
        formats::writeExrRgba32(path, image.width, image.height, image.rgba);
        return;
    }
    const std::vector<float> cloud = algo::cloudLayer(image.rgba, image.background);
    formats::writeExrFloat32(path, image.width, image.height,
                             {{{"R", "G", "B", "A"}, image.rgba},
                              {{"cloud.R", "cloud.G", "cloud.B", "cloud.A"}, cloud},
                              {{"background.R", "background.G", "background.B"},
                               image.background}});
}

class WriteImageNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        if (!writesThisFrame(ctx)) return;
        const auto image = ctx.input<ImageData>("image");
        const std::filesystem::path path = ctx.outputPath("file");
        util::AtomicOutput out(path);
        if (isExr(path.string())) {
            writeExr(out.tempPath().string(), *image);
        } else {
            algo::DisplaySettings display;
            display.exposure = ctx.params().getFloat("exposure");
            display.curve = algo::toneCurveFromName(ctx.params().getString("toneMap"));
            display.dither = ctx.params().getBool("dither");
            display.seed = static_cast<std::uint64_t>(ctx.frame());
            const std::vector<std::uint8_t> rgb =
                algo::displayRgb8(image->rgba, image->width, image->height, display);
            ctx.checkCancelled();
            formats::writePngRgb8(out.tempPath().string(), image->width, image->height, rgb);
        }
        out.commit();
        ctx.setOutput("files", std::make_shared<TextData>(path.string()));
    }
};

}  // namespace

void registerWriteImageNode(Registry& registry)
{
    NodeDecl d = writerDecl(
        "WriteImage",
        "Writes an image of linear radiance (e.g. the Renderer's). A file ending in .png is an "
        "8-bit sRGB PNG: each RGB value v becomes round(255 sRGB(toneMap(2^exposure v))) plus "
        "an optional +-1 triangular dither seeded by the frame; alpha is dropped (the image is "
        "already composited). A file ending in .exr is a linear OpenEXR image, 32-bit floats "
        "unchanged (exposure, toneMap and dither do not apply), ZIP-compressed, for "
        "compositing: R, G, B, A hold the image as it is (the Renderer's beauty: cloud over "
        "sky and ground). An image with a background (the Renderer's) adds the layers "
        "cloud.R/G/B/A (the cloud alone, premultiplied: cloud = beauty - (1 - alpha) x "
        "background) and background.R/G/B (sky and ground with the cloud's shadow), so a "
        "compositor can put the cloud over a plate (docs/rendering.md, Compositing the EXR "
        "layers). Top row first. #### in the name becomes the frame number; the file "
        "appears atomically.",
        port("image", "Image", "linear radiance RGBA, with a background where it has one"),
        "image.####.png");
    d.params.push_back(floatParam("exposure", 0.0, "stops",
                                  "radiance is multiplied by 2^exposure before the tone map",
                                  -20, 20));
    d.params.push_back(stringParam("toneMap", "aces",
                                   "filmic curve: aces (Narkowicz fit), hable (Uncharted 2, "
                                   "white 11.2) or clamp (none)",
                                   {"aces", "hable", "clamp"}));
    d.params.push_back(boolParam("dither", true, "add +-1 code-value triangular dither (no banding)"));
    d.validate = [](const ParamSet& p, const ParamChecker& check) {
        const std::string& file = p.getString("file");
        if (!endsWith(file, ".png") && !isExr(file))
            check.fail("file", "'" + file + "' must end in .png (8-bit sRGB) or .exr (linear float)");
    };
    d.create = [] { return std::make_unique<WriteImageNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
