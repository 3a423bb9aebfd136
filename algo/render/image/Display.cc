#include "algo/render/image/Display.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "algo/CounterRandom.h"

namespace cg::algo {

namespace {

/// 255 srgbEncode(y) for y in [0, 1] through single-precision pow, within 1e-4 of the
/// double-precision value (float rounding of y and powf's error, each ~1e-7 relative).
double fastSrgb255(double y)
{
    if (!(y > 0.0031308)) return 255.0 * srgbEncode(y);
    if (y >= 1.0) return 255.0;
    return 255.0 * (1.055 * double(std::pow(float(y), 1.0f / 2.4f)) - 0.055);
}

/// The code value of a channel: round(clamp(255 srgbEncode(y) + dither)), the same byte as
/// the double-precision formula gives. The float estimate decides it unless it lies within
/// a margin (10x its error) of a rounding boundary; then the double formula does.
std::uint8_t codeValue(double y, double dither)
{
    constexpr double kMargin = 1e-3;
    double x = std::clamp(fastSrgb255(y) + dither, 0.0, 255.0);
    if (std::fabs(x - std::floor(x) - 0.5) < kMargin)
        x = std::clamp(255.0 * srgbEncode(y) + dither, 0.0, 255.0);
    return static_cast<std::uint8_t>(std::lround(x));
}

/// The triangular dither (on (-1, 1) code values) of channel k, or 0 without dither.
double dither(const DisplaySettings& s, std::uint64_t k)
{
    if (!s.dither) return 0.0;
    return counterUniform(s.seed, 2 * k, 0x44495448ull) -
           counterUniform(s.seed, 2 * k + 1, 0x44495448ull);
}

/// Pixels [first, last) through the OCIO display: the exposed RGB in a buffer, transformed,
/// then quantised with the same dither.
void encodeOcio(const std::vector<float>& rgba, double scale, const DisplaySettings& s,
                std::size_t first, std::size_t last, std::vector<std::uint8_t>& out)
{
    std::vector<float> rgb(3 * (last - first));
    for (std::size_t i = first; i < last; ++i)
        for (std::size_t c = 0; c < 3; ++c)
            rgb[3 * (i - first) + c] = static_cast<float>(scale * rgba[i * 4 + c]);
    s.ocio->apply(rgb.data(), last - first);
    for (std::size_t i = first; i < last; ++i)
        for (std::size_t c = 0; c < 3; ++c) {
            const double v = 255.0 * double(rgb[3 * (i - first) + c]) + dither(s, i * 3 + c);
            out[i * 3 + c] = static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 255.0)));
        }
}

}  // namespace

std::vector<std::uint8_t> displayRgb8(const std::vector<float>& rgba, int width, int height,
                                      const DisplaySettings& s)
{
    if (width < 1 || height < 1 ||
        rgba.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4)
        throw std::invalid_argument("displayRgb8: " + std::to_string(rgba.size()) +
                                    " floats do not make a " + std::to_string(width) + " x " +
                                    std::to_string(height) + " RGBA image");
    const double scale = std::exp2(s.exposure);
    const std::size_t n = rgba.size() / 4;
    std::vector<std::uint8_t> out(n * 3);
    // Every pixel writes only its own bytes and the dither is keyed by its index: the same
    // bytes for any thread count.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          if (s.ocio) {
                              encodeOcio(rgba, scale, s, r.begin(), r.end(), out);
                              return;
                          }
                          for (std::size_t i = r.begin(); i < r.end(); ++i)
                              for (std::size_t c = 0; c < 3; ++c) {
                                  const double y = toneMap(scale * rgba[i * 4 + c], s.curve);
                                  out[i * 3 + c] = codeValue(y, dither(s, i * 3 + c));
                              }
                      });
    return out;
}

}  // namespace cg::algo
