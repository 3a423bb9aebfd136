// displayRgb8: every byte equals the double-precision formula round(clamp(255 srgbEncode(
// toneMap(2^exposure v)) + dither)), also for values whose code value sits on a rounding edge.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "algo/CounterRandom.h"
#include "algo/render/image/Display.h"
#include "algo/render/image/ToneMap.h"

namespace cg::algo {
namespace {

/// The formula of Display.h, in double precision throughout.
std::vector<std::uint8_t> reference(const std::vector<float>& rgba, const DisplaySettings& s)
{
    std::vector<std::uint8_t> out(rgba.size() / 4 * 3);
    for (std::size_t i = 0; i < rgba.size() / 4; ++i)
        for (std::size_t c = 0; c < 3; ++c) {
            const double v =
                255.0 * srgbEncode(toneMap(std::exp2(s.exposure) * rgba[i * 4 + c], s.curve));
            double d = 0.0;
            if (s.dither) {
                const std::uint64_t k = i * 3 + c;
                d = counterUniform(s.seed, 2 * k, 0x44495448ull) -
                    counterUniform(s.seed, 2 * k + 1, 0x44495448ull);
            }
            out[i * 3 + c] = static_cast<std::uint8_t>(std::lround(std::clamp(v + d, 0.0, 255.0)));
        }
    return out;
}

TEST(Display, EqualsTheDoublePrecisionFormulaByteForByte)
{
    // Radiance from 1e-6 to 100, log-spaced, plus 0, negative and NaN.
    std::vector<float> rgba;
    for (int k = 0; k < 30000; ++k) {
        const float v = static_cast<float>(1e-6 * std::pow(1e8, k / 29999.0));
        rgba.insert(rgba.end(), {v, v * 0.5f, v * 2.0f, 1.0f});
    }
    rgba.insert(rgba.end(), {0.0f, -1.0f, std::nanf(""), 1.0f});
    const int width = static_cast<int>(rgba.size() / 4);
    for (const ToneCurve curve : {ToneCurve::Aces, ToneCurve::Hable, ToneCurve::Clamp})
        for (const bool dither : {false, true})
            for (const double exposure : {-2.0, 0.0, 1.5}) {
                DisplaySettings s;
                s.curve = curve;
                s.dither = dither;
                s.exposure = exposure;
                s.seed = 17;
                EXPECT_EQ(displayRgb8(rgba, width, 1, s), reference(rgba, s))
                    << "curve " << int(curve) << " dither " << dither << " exposure " << exposure;
            }
}

TEST(Display, ValuesOnARoundingEdgeRoundAsInDoublePrecision)
{
    // Without curve or dither, v is on the edge between code values k and k + 1 when
    // 255 srgbEncode(v) = k + 0.5; floats just below, at and above each edge.
    std::vector<float> rgba;
    for (int k = 0; k < 255; ++k) {
        const float edge = static_cast<float>(srgbDecode((k + 0.5) / 255.0));
        float below = edge, above = edge;
        for (int step = 0; step < 4; ++step) {
            rgba.insert(rgba.end(), {below, above, edge, 1.0f});
            below = std::nextafter(below, 0.0f);
            above = std::nextafter(above, 1.0f);
        }
    }
    DisplaySettings s;
    s.curve = ToneCurve::Clamp;
    s.dither = false;
    const int width = static_cast<int>(rgba.size() / 4);
    const std::vector<std::uint8_t> out = displayRgb8(rgba, width, 1, s);
    EXPECT_EQ(out, reference(rgba, s));
    // Both sides of the edges occur: the edges are where the float estimate is not trusted.
    int lower = 0, upper = 0;
    for (int k = 0; k < 255; ++k) {
        lower += out[static_cast<std::size_t>(k) * 12 + 9] == k;       // 3 floats below
        upper += out[static_cast<std::size_t>(k) * 12 + 10] == k + 1;  // 3 floats above
    }
    EXPECT_GT(lower, 200);
    EXPECT_GT(upper, 200);
}

}  // namespace
}  // namespace cg::algo
