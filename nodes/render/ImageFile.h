#pragma once
/// An image as a file, chosen by its extension: .png is 8-bit sRGB through the display
/// transform (exposure, tone curve, dither), .exr is linear float, with the cloud and
/// background layers when the image has a background. Shared by WriteImage and the Python
/// module's write_image, so both write the same bytes.

#include <filesystem>
#include <string>

#include "algo/render/image/Display.h"

namespace cg {

class ImageData;
class ParamSet;

/// The display transform a WriteImage node's parameters (exposure, toneMap, dither) give its
/// PNG of `frame` (the dither's seed). `cloudgraph serve`'s preview shows the same.
algo::DisplaySettings writeImageDisplay(const ParamSet& params, int frame);

/// WriteImage's OpenColorIO choice (ocioConfig, ocioInput, ocioDisplay, ocioView).
algo::OcioChoice writeImageOcio(const ParamSet& params);

/// Whether `file` ends in .png or .exr.
bool isImageFileName(const std::string& file);

/// Writes `image` to `path` atomically (the file appears whole or not at all). `display`
/// applies to PNG only. Throws std::invalid_argument for another extension.
void writeImageFile(const std::filesystem::path& path, const ImageData& image,
                    const algo::DisplaySettings& display);

}  // namespace cg
