#pragma once
/// What `cloudgraph serve`'s preview shows of a cooked value: an image through the display
/// transform its WriteImage uses, a density map as grey levels, particles as points seen
/// from the side. Pictures only: nothing here is written to a file the graph names.

#include <cstdint>
#include <optional>
#include <vector>

#include "algo/render/image/Display.h"
#include "core/Data.h"

namespace cg::cli {

struct PreviewPicture {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgb;  ///< 3 bytes a pixel, top row first
};

/// The widest picture of points, in pixels (the height follows the points' extent).
inline constexpr int kPointsPictureWidth = 640;

/// The picture of `value`, or nullopt for a type the preview does not draw:
/// - Image: through `display` (exposure, tone curve, dither);
/// - Map2D: one pixel a cell, value 0 black to 1 white, +y up (north at the top);
/// - VapourParticles, Condensation, CloudParticles: every particle a point seen from the
///   south (x to the right, z up) on a dark ground, the picture fitted to the particles'
///   extent at one scale for both axes, brighter where more particles fall on a pixel
///   (log of the count); Condensation draws vapour blue and condensed particles white.
std::optional<PreviewPicture> previewPicture(const DataPtr& value,
                                             const algo::DisplaySettings& display);

}  // namespace cg::cli
