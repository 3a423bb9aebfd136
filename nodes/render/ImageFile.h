#pragma once
/// An image as a file, chosen by its extension: .png is 8-bit sRGB through the display
/// transform (exposure, tone curve, dither), .exr is linear float, with the cloud and
/// background layers when the image has a background. Shared by WriteImage and the Python
/// module's write_image, so both write the same bytes.

#include <filesystem>
#include <string>

#include "algo/render/Display.h"

namespace cg {

class ImageData;

/// Whether `file` ends in .png or .exr.
bool isImageFileName(const std::string& file);

/// Writes `image` to `path` atomically (the file appears whole or not at all). `display`
/// applies to PNG only. Throws std::invalid_argument for another extension.
void writeImageFile(const std::filesystem::path& path, const ImageData& image,
                    const algo::DisplaySettings& display);

}  // namespace cg
