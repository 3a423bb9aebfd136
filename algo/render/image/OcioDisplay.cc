#include "algo/render/image/OcioDisplay.h"

#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include <OpenColorIO/OpenColorIO.h>

namespace cg::algo {

namespace OCIO = OCIO_NAMESPACE;

namespace {

/// The built-in config. The scene reference is linear Rec.709 (the Renderer's working space);
/// ACEScg is there for images in it. "ACES 1.0 - SDR Video" takes Rec.709 to ACES2065-1
/// through AP1 (the inverse of OCIO's AP1-to-Rec.709 Bradford matrix, then ACEScg's own),
/// applies the ACES 1.0 SDR video output transform (RRT + ODT, to CIE XYZ D65) and encodes
/// for an sRGB display; "Un-tone-mapped" is the sRGB curve (IEC 61966-2-1) alone.
const char* const kBuiltin = R"(ocio_profile_version: 2.1

description: CloudGraph's built-in config (linear Rec.709 scene space, sRGB display)

roles:
  default: Linear Rec.709 (sRGB)
  scene_linear: Linear Rec.709 (sRGB)
  data: Raw
  color_timing: Linear Rec.709 (sRGB)
  compositing_log: Linear Rec.709 (sRGB)
  color_picking: sRGB - Display

displays:
  sRGB - Display:
    - !<View> {name: ACES 1.0 - SDR Video, colorspace: ACES 1.0 - SDR Video - sRGB}
    - !<View> {name: Un-tone-mapped, colorspace: sRGB - Display}
    - !<View> {name: Raw, colorspace: Raw}

active_displays: [sRGB - Display]
active_views: [ACES 1.0 - SDR Video, Un-tone-mapped, Raw]

colorspaces:
  - !<ColorSpace>
    name: Linear Rec.709 (sRGB)
    family: Scene-linear
    encoding: scene-linear
    description: linear, Rec.709 primaries, D65 white (the Renderer's working space)

  - !<ColorSpace>
    name: ACEScg
    family: Scene-linear
    encoding: scene-linear
    to_scene_reference: !<BuiltinTransform> {style: UTILITY - ACES-AP1_to_LINEAR-REC709_BFD}

  - !<ColorSpace>
    name: sRGB - Display
    family: Display
    encoding: sdr-video
    from_scene_reference: !<ExponentWithLinearTransform> {gamma: 2.4, offset: 0.055, direction: inverse}

  - !<ColorSpace>
    name: ACES 1.0 - SDR Video - sRGB
    family: Display
    encoding: sdr-video
    from_scene_reference: !<GroupTransform>
      children:
        - !<BuiltinTransform> {style: UTILITY - ACES-AP1_to_LINEAR-REC709_BFD, direction: inverse}
        - !<BuiltinTransform> {style: ACEScg_to_ACES2065-1}
        - !<BuiltinTransform> {style: ACES-OUTPUT - ACES2065-1_to_CIE-XYZ-D65 - SDR-VIDEO_1.0}
        - !<BuiltinTransform> {style: DISPLAY - CIE-XYZ-D65_to_sRGB}

  - !<ColorSpace>
    name: Raw
    family: Utility
    encoding: data
    isdata: true
)";

OCIO::ConstConfigRcPtr loadConfig(const std::string& file)
{
    try {
        if (!file.empty()) return OCIO::Config::CreateFromFile(file.c_str());
        std::istringstream text(builtinOcioConfig());
        return OCIO::Config::CreateFromStream(text);
    } catch (const OCIO::Exception& e) {
        throw std::invalid_argument((file.empty() ? std::string("the built-in OCIO config")
                                                  : "OCIO config '" + file + "'") +
                                    ": " + e.what());
    }
}

bool hasView(const OCIO::ConstConfigRcPtr& config, const std::string& display,
             const std::string& view)
{
    for (int i = 0; i < config->getNumViews(display.c_str()); ++i)
        if (view == config->getView(display.c_str(), i)) return true;
    return false;
}

}  // namespace

struct OcioDisplay::Processor {
    OCIO::ConstCPUProcessorRcPtr cpu;
};

const std::string& builtinOcioConfig()
{
    static const std::string text = kBuiltin;
    return text;
}

std::string ocioConfigFromEnvironment()
{
    const char* env = std::getenv("OCIO");
    return env != nullptr ? env : "";
}

OcioDisplay::OcioDisplay(const OcioChoice& choice) : mProcessor(std::make_unique<Processor>())
{
    const std::string file =
        choice.configFile.empty() ? ocioConfigFromEnvironment() : choice.configFile;
    const OCIO::ConstConfigRcPtr config = loadConfig(file);
    const std::string where =
        file.empty() ? std::string("the built-in OCIO config") : "OCIO config '" + file + "'";
    mDisplay = choice.display.empty() ? config->getDefaultDisplay() : choice.display;
    if (config->getNumViews(mDisplay.c_str()) == 0)
        throw std::invalid_argument(where + " has no display '" + mDisplay + "'");
    mView = choice.view.empty() ? config->getDefaultView(mDisplay.c_str()) : choice.view;
    if (!hasView(config, mDisplay, mView))
        throw std::invalid_argument(where + " has no view '" + mView + "' on display '" + mDisplay +
                                    "'");
    if (!config->getColorSpace(choice.input.c_str()))
        throw std::invalid_argument(where + " has no colour space '" + choice.input + "'");
    try {
        const OCIO::DisplayViewTransformRcPtr t = OCIO::DisplayViewTransform::Create();
        t->setSrc(choice.input.c_str());
        t->setDisplay(mDisplay.c_str());
        t->setView(mView.c_str());
        mProcessor->cpu = config->getProcessor(t)->getDefaultCPUProcessor();
    } catch (const OCIO::Exception& e) {
        throw std::invalid_argument(where + ": " + e.what());
    }
}

OcioDisplay::~OcioDisplay() = default;

void OcioDisplay::apply(float* rgb, std::size_t pixels) const
{
    OCIO::PackedImageDesc image(rgb, static_cast<long>(pixels), 1, 3);
    mProcessor->cpu->apply(image);
}

}  // namespace cg::algo
