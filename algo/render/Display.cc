#include "algo/render/Display.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "algo/CounterRandom.h"

namespace cg::algo {

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
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t i = r.begin(); i < r.end(); ++i) {
                for (std::size_t c = 0; c < 3; ++c) {
                    const double v = 255.0 * srgbEncode(toneMap(scale * rgba[i * 4 + c], s.curve));
                    double d = 0.0;
                    if (s.dither) {  // triangular PDF on (−1, 1) code values
                        const std::uint64_t k = i * 3 + c;
                        d = counterUniform(s.seed, 2 * k, 0x44495448ull) -
                            counterUniform(s.seed, 2 * k + 1, 0x44495448ull);
                    }
                    out[i * 3 + c] =
                        static_cast<std::uint8_t>(std::lround(std::clamp(v + d, 0.0, 255.0)));
                }
            }
        });
    return out;
}

}  // namespace cg::algo
