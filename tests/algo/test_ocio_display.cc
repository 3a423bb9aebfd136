// OpenColorIO display transforms: the built-in config's un-tone-mapped view is the sRGB curve
// (IEC 61966-2-1) in closed form; its ACES view keeps greys neutral, puts scene grey at ACES's
// 10% of display white, rolls highlights off below 1 and stays near Narkowicz's fit of the same
// transform (our `aces` curve); a config file of our own gives its transform exactly; what is
// missing is named; displayRgb8 quantises OCIO's values.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "algo/render/image/Display.h"
#include "algo/render/image/OcioDisplay.h"
#include "algo/render/image/ToneMap.h"
#include "support/TestUtil.h"

namespace cg {

namespace {

float through(const algo::OcioDisplay& d, float v)
{
    float rgb[3] = {v, v, v};
    d.apply(rgb, 1);
    EXPECT_NEAR(rgb[0], rgb[1], 1e-5f);
    EXPECT_NEAR(rgb[1], rgb[2], 1e-5f);
    return rgb[1];
}

double srgb(double v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055; }

algo::OcioChoice builtin(const std::string& view)
{
    algo::OcioChoice c;
    c.view = view;
    return c;
}

}  // namespace

TEST(OcioDisplay, TheBuiltInUntonemappedViewIsTheSrgbCurve)
{
    const algo::OcioDisplay d(builtin("Un-tone-mapped"));
    EXPECT_EQ(d.display(), "sRGB - Display");
    for (float v : {0.0f, 0.001f, 0.01f, 0.18f, 0.5f, 1.0f})
        EXPECT_NEAR(through(d, v), srgb(v), 2e-4) << v;
}

TEST(OcioDisplay, TheBuiltInAcesViewRollsOffAndAgreesWithTheFit)
{
    const algo::OcioDisplay d(builtin(""));  // the display's default view
    EXPECT_EQ(d.view(), "ACES 1.0 - SDR Video");
    float last = -1.0f;
    for (float v : {0.0f, 0.01f, 0.05f, 0.18f, 0.5f, 1.0f, 4.0f, 16.0f}) {
        const float y = through(d, v);
        EXPECT_GT(y, last) << v;  // monotone
        last = y;
        if (v >= 0.05f && v <= 1.0f) {
            // Narkowicz's fit of the same RRT + ODT (our `aces` curve, its input scaled by
            // 0.6) runs a little brighter on mid-tones: 0.054 at 0.18, measured.
            EXPECT_NEAR(y, srgb(algo::toneMap(v, algo::ToneCurve::Aces)), 0.06) << v;
        }
    }
    EXPECT_LT(last, 1.0f);  // 16 times diffuse white still below the display's white
    // ACES 1.0's SDR video output puts scene grey 0.18 at 10 cd/m^2 of a 100 cd/m^2 display:
    // 0.1 of display white once the sRGB encoding is undone.
    const double grey = through(d, 0.18f);
    EXPECT_NEAR(std::pow((grey + 0.055) / 1.055, 2.4), 0.10, 0.01);
}

TEST(OcioDisplay, AConfigFileGivesItsOwnTransformAndMissingNamesAreRefused)
{
    test::TempDir dir;
    const std::string file = (dir / "double.ocio").string();
    std::ofstream(file) << R"(ocio_profile_version: 2
roles:
  default: lin
  scene_linear: lin
displays:
  Double:
    - !<View> {name: Twice, colorspace: twice}
colorspaces:
  - !<ColorSpace>
    name: lin
  - !<ColorSpace>
    name: twice
    from_scene_reference: !<CDLTransform> {slope: [2, 2, 2]}
)";
    algo::OcioChoice c;
    c.configFile = file;
    c.input = "lin";
    const algo::OcioDisplay d(c);
    EXPECT_EQ(d.display(), "Double");
    EXPECT_NEAR(through(d, 0.1f), 0.2f, 1e-6f);

    const auto refused = [](algo::OcioChoice bad, const std::string& what) {
        try {
            const algo::OcioDisplay accepted(bad);
            ADD_FAILURE() << what << " accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
        }
    };
    algo::OcioChoice bad = c;
    bad.view = "Thrice";
    refused(bad, "no view 'Thrice'");
    bad = c;
    bad.display = "Cinema";
    refused(bad, "no display 'Cinema'");
    bad = c;
    bad.input = "ACEScg";
    refused(bad, "no colour space 'ACEScg'");
    bad = c;
    bad.configFile = (dir / "missing.ocio").string();
    refused(bad, "missing.ocio");
}

TEST(OcioDisplay, DisplayRgb8QuantisesTheDisplayValues)
{
    algo::DisplaySettings s;
    s.dither = false;
    s.ocio = std::make_shared<algo::OcioDisplay>(builtin("Un-tone-mapped"));
    const std::vector<float> rgba = {0.18f, 0.5f, 1.0f, 1.0f, 0.0f, 0.001f, 4.0f, 1.0f};
    const std::vector<std::uint8_t> rgb = algo::displayRgb8(rgba, 2, 1, s);
    for (std::size_t i = 0; i < 6; ++i) {
        const double v = std::min(1.0, srgb(rgba[i + i / 3]));
        EXPECT_EQ(rgb[i], static_cast<std::uint8_t>(std::lround(255.0 * v))) << i;
    }
}

}  // namespace cg
