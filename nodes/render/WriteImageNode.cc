// WriteImage: a linear radiance image to an 8-bit sRGB PNG (exposure, filmic tone map) or to a
// linear OpenEXR file, chosen by the file's extension; an image with a background becomes a
// multi-layer EXR (beauty, cloud, background).

#include <filesystem>
#include <memory>
#include <string>

#include "algo/render/image/Display.h"
#include "algo/render/image/OcioDisplay.h"
#include "core/CoreData.h"
#include "core/Hash.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "formats/FileHash.h"
#include "formats/FormatError.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/Image.h"
#include "nodes/io/WriterSupport.h"
#include "nodes/render/ImageFile.h"
#include "nodes/render/RenderNodes.h"

namespace cg {

namespace {

/// An OCIO config larger than this is refused (studio configs are a few hundred kB; their
/// LUTs are separate files).
constexpr std::uint64_t kMaxOcioConfigBytes = std::uint64_t{16} << 20;

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

/// The OCIO config, display, view and colour space exist: refused at load otherwise, naming
/// the parameter.
void checkOcio(const ParamSet& p, const ParamChecker& check)
{
    try {
        algo::OcioDisplay display(writeImageOcio(p));
    } catch (const std::invalid_argument& e) {
        const std::string what = e.what();
        const char* param = what.find("no display") != std::string::npos        ? "ocioDisplay"
                            : what.find("no view") != std::string::npos         ? "ocioView"
                            : what.find("no colour space") != std::string::npos ? "ocioInput"
                                                                                : "ocioConfig";
        check.fail(param, what);
    }
}

/// With toneMap ocio, the config's content is in the key (the file given or $OCIO's), so
/// editing it redraws the PNGs.
void hashOcioConfig(const ParamSet& p, Hasher& h)
{
    if (p.getString("toneMap") != "ocio") return;
    std::string file = p.getString("ocioConfig");
    if (file.empty()) file = algo::ocioConfigFromEnvironment();
    if (file.empty()) return;
    try {
        h.str("ocioConfig").u64(formats::fileContentHash(file, kMaxOcioConfigBytes, "OCIO config"));
    } catch (const formats::FormatError&) {
        h.str("unreadable OCIO config").str(file);
    }
}

}  // namespace

algo::OcioChoice writeImageOcio(const ParamSet& params)
{
    algo::OcioChoice choice;
    choice.configFile = params.getString("ocioConfig");
    choice.input = params.getString("ocioInput");
    choice.display = params.getString("ocioDisplay");
    choice.view = params.getString("ocioView");
    return choice;
}

algo::DisplaySettings writeImageDisplay(const ParamSet& params, int frame)
{
    algo::DisplaySettings display;
    display.exposure = params.getFloat("exposure");
    if (params.getString("toneMap") == "ocio")
        display.ocio = std::make_shared<algo::OcioDisplay>(writeImageOcio(params));
    else
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
                                   "white 11.2), clamp (none), or ocio: OpenColorIO's display "
                                   "transform (ocioConfig, ocioDisplay, ocioView)",
                                   {"aces", "hable", "clamp", "ocio"}));
    d.params.push_back(inputFileParam(
        "ocioConfig", "",
        "toneMap ocio: an OCIO config file; empty = the one $OCIO names, else the built-in "
        "config (display 'sRGB - Display', views 'ACES 1.0 - SDR Video' and 'Un-tone-mapped')"));
    d.params.push_back(stringParam("ocioInput", "Linear Rec.709 (sRGB)",
                                   "toneMap ocio: the config's name of the image's colour space "
                                   "(the Renderer's is linear Rec.709)"));
    d.params.push_back(
        stringParam("ocioDisplay", "", "toneMap ocio: the display; empty = the config's default"));
    d.params.push_back(
        stringParam("ocioView", "", "toneMap ocio: the view; empty = the display's default view"));
    d.params.push_back(
        boolParam("dither", true, "add +-1 code-value triangular dither (no banding)"));
    d.validate = [](const ParamSet& p, const ParamChecker& check) {
        const std::string& file = p.getString("file");
        if (!isImageFileName(file))
            check.fail("file",
                       "'" + file + "' must end in .png (8-bit sRGB) or .exr (linear float)");
        if (p.getString("toneMap") == "ocio") checkOcio(p, check);
    };
    d.hashExtra = hashOcioConfig;
    d.create = [] { return std::make_unique<WriteImageNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
