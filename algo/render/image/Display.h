#pragma once
/// Display encoding of rendered images: exposure, tone curve, sRGB and dither to 8 bits.

#include <cstdint>
#include <memory>
#include <vector>

#include "algo/render/image/OcioDisplay.h"
#include "algo/render/image/ToneMap.h"

namespace cg::algo {

/// How linear radiance becomes 8-bit display values.
struct DisplaySettings {
    double exposure = 0.0;  ///< stops: radiance is multiplied by 2^exposure
    ToneCurve curve = ToneCurve::Aces;
    bool dither = true;      ///< ±1 code-value triangular dither against banding (counter-based)
    std::uint64_t seed = 0;  ///< dither seed
    /// When set, OpenColorIO's display transform replaces the curve and the sRGB encoding:
    /// q = round(255 ocio(2^exposure v) + dither).
    std::shared_ptr<const OcioDisplay> ocio;
};

/// RGB8 from linear RGBA floats (4 per pixel; alpha ignored, the image is already
/// composited): q = round(255 srgbEncode(toneMap(2^exposure v)) + dither), or with an OCIO
/// display round(255 ocio(2^exposure v) + dither), clamped to 0..255.
/// Row order is kept. Throws std::invalid_argument if rgba.size() != 4 width height.
std::vector<std::uint8_t> displayRgb8(const std::vector<float>& rgba, int width, int height,
                                      const DisplaySettings& settings);

}  // namespace cg::algo
