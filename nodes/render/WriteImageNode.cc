// WriteImage: a linear radiance image to an 8-bit sRGB PNG (exposure, filmic tone map) or to a
// linear OpenEXR file, chosen by the file's extension; an image with a background becomes a
// multi-layer EXR (beauty, cloud, background).

#include <filesystem>
#include <memory>
#include <string>

#include "algo/render/image/Display.h"
#include "core/CoreData.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/Image.h"
#include "nodes/io/WriterSupport.h"
#include "nodes/render/ImageFile.h"
#include "nodes/render/RenderNodes.h"

namespace cg {

namespace {

class WriteImageNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        if (!writesThisFrame(ctx)) return;
        const auto image = ctx.input<ImageData>("image");
        const std::filesystem::path path = ctx.outputPath("file");
        writeImageFile(path, *image, writeImageDisplay(ctx.params(), ctx.frame()));
        ctx.setOutput("files", std::make_shared<TextData>(path.string()));
    }
};

}  // namespace

algo::DisplaySettings writeImageDisplay(const ParamSet& params, int frame)
{
    algo::DisplaySettings display;
    display.exposure = params.getFloat("exposure");
    display.curve = algo::toneCurveFromName(params.getString("toneMap"));
    display.dither = params.getBool("dither");
    display.seed = static_cast<std::uint64_t>(frame);
    return display;
}

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
                                  "radiance is multiplied by 2^exposure before the tone map", -20,
                                  20));
    d.params.push_back(stringParam("toneMap", "aces",
                                   "filmic curve: aces (Narkowicz fit), hable (Uncharted 2, "
                                   "white 11.2) or clamp (none)",
                                   {"aces", "hable", "clamp"}));
    d.params.push_back(
        boolParam("dither", true, "add +-1 code-value triangular dither (no banding)"));
    d.validate = [](const ParamSet& p, const ParamChecker& check) {
        const std::string& file = p.getString("file");
        if (!isImageFileName(file))
            check.fail("file",
                       "'" + file + "' must end in .png (8-bit sRGB) or .exr (linear float)");
    };
    d.create = [] { return std::make_unique<WriteImageNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
