#pragma once
/// Display encoding of rendered images and 8-bit sRGB PNG files.

#include <cstdint>
#include <string>
#include <vector>

#include "nodes/algo/ToneMap.h"

namespace cg::algo {

/// How linear radiance becomes 8-bit display values.
struct DisplaySettings {
    double exposure = 0.0;  ///< stops: radiance is multiplied by 2^exposure
    ToneCurve curve = ToneCurve::Aces;
    bool dither = true;     ///< ±1 code-value triangular dither against banding (counter-based)
    std::uint64_t seed = 0; ///< dither seed
};

/// RGB8 from linear RGBA floats (4 per pixel; alpha ignored, the image is already
/// composited): q = round(255 srgbEncode(toneMap(2^exposure v)) + dither), clamped to 0..255.
/// Row order is kept. Throws std::invalid_argument if rgba.size() != 4 width height.
std::vector<std::uint8_t> displayRgb8(const std::vector<float>& rgba, int width, int height,
                                      const DisplaySettings& settings);

/// Writes an 8-bit RGB PNG (top row first) tagged sRGB, exactly to `path`. Throws
/// std::runtime_error naming the file on failure, std::invalid_argument on bad sizes.
void writePngRgb8(const std::string& path, int width, int height,
                  const std::vector<std::uint8_t>& rgb);

struct Rgb8Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgb;  ///< 3 bytes per pixel, top row first
};

/// Reads an 8-bit RGB PNG (tests and tools). Throws std::runtime_error for anything else.
Rgb8Image readPngRgb8(const std::string& path);

}  // namespace cg::algo
