// WriteImage: a linear radiance image to an 8-bit sRGB PNG (exposure, filmic tone map).

#include <filesystem>
#include <memory>

#include "core/AtomicFile.h"
#include "core/CoreData.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/algo/RenderPng.h"
#include "nodes/data/Image.h"
#include "nodes/io/WriterSupport.h"
#include "nodes/render/RenderNodes.h"

namespace cg {

namespace {

class WriteImageNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        if (!writesThisFrame(ctx)) return;
        const auto image = ctx.input<ImageData>("image");
        algo::DisplaySettings display;
        display.exposure = ctx.params().getFloat("exposure");
        display.curve = algo::toneCurveFromName(ctx.params().getString("toneMap"));
        display.dither = ctx.params().getBool("dither");
        display.seed = static_cast<std::uint64_t>(ctx.frame());
        const std::vector<std::uint8_t> rgb =
            algo::displayRgb8(image->rgba, image->width, image->height, display);
        ctx.checkCancelled();

        const std::filesystem::path path = ctx.outputPath("file");
        AtomicOutput out(path);
        algo::writePngRgb8(out.tempPath().string(), image->width, image->height, rgb);
        out.commit();
        ctx.setOutput("files", std::make_shared<TextData>(path.string()));
    }
};

}  // namespace

void registerWriteImageNode(Registry& registry)
{
    NodeDecl d = writerDecl(
        "WriteImage",
        "Writes an image of linear radiance (e.g. the Renderer's) as an 8-bit sRGB PNG: each "
        "RGB value v becomes round(255 sRGB(toneMap(2^exposure v))) plus an optional +-1 "
        "triangular dither seeded by the frame; alpha is dropped (the image is already "
        "composited). Top row first. #### in the name becomes the frame number; the file "
        "appears atomically. EXR output is not implemented (OpenEXR is not a dependency).",
        port("image", "Image", "linear radiance RGBA"), "image.####.png");
    d.params.push_back(floatParam("exposure", 0.0, "stops",
                                  "radiance is multiplied by 2^exposure before the tone map",
                                  -20, 20));
    d.params.push_back(stringParam("toneMap", "aces",
                                   "filmic curve: aces (Narkowicz fit), hable (Uncharted 2, "
                                   "white 11.2) or clamp (none)",
                                   {"aces", "hable", "clamp"}));
    d.params.push_back(boolParam("dither", true, "add +-1 code-value triangular dither (no banding)"));
    d.create = [] { return std::make_unique<WriteImageNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
