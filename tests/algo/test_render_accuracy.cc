// The fast mode against the reference path tracer on a small cumulus (the synthetic cloud of
// graphs/cumulus_still.json at half its resolution), with the sun in front of the camera,
// beside it and behind it: the fast mode's mean relative luminance error over the cloud's
// pixels must stay within 10% and its 90th percentile within 25%, issue 16's goal.
// bench/render_error measures the same on larger volumes (docs/rendering.md).

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "algo/render/integrators/RenderPathTrace.h"
#include "algo/render/integrators/RenderVolume.h"
#include "algo/render/metrics/RenderError.h"

namespace cg {

namespace {

constexpr int kWidth = 64, kHeight = 48;
constexpr int kReferenceSamples = 1024;  // per half, two halves with independent seeds

/// The still's cumulus at half the resolution, at kWidth x kHeight.
algo::ErrorScene smallCumulus()
{
    algo::ErrorScene out = algo::stillCumulusScene(20.0);
    out.settings.camera.width = kWidth;
    out.settings.camera.height = kHeight;
    out.settings.pathTrace.samples = kReferenceSamples;
    return out;
}

class FastModeAccuracy : public ::testing::TestWithParam<std::string> {};

TEST_P(FastModeAccuracy, StaysWithinTenPercentOfThePathTracer)
{
    algo::ErrorScene scene = smallCumulus();
    scene.settings.sun.direction = algo::sunAroundCamera(scene.settings.camera, GetParam());
    const algo::RenderedImage fast = algo::renderFogVolume(*scene.grid, scene.settings);
    algo::RenderedImage half[2];
    for (int i = 0; i < 2; ++i) {
        algo::RenderSettings h = scene.settings;
        h.march.seed = static_cast<std::uint64_t>(i);
        half[i] = algo::renderPathTraced(*scene.grid, h);
    }
    algo::RenderedImage reference = half[0];
    for (std::size_t i = 0; i < reference.rgba.size(); ++i)
        reference.rgba[i] = 0.5f * (half[0].rgba[i] + half[1].rgba[i]);

    const algo::LuminanceError e = algo::luminanceError(fast, reference);
    const double noise = algo::referenceNoise(half[0], half[1]);
    EXPECT_GT(e.pixels, 200u);
    EXPECT_LT(noise, 0.05) << "the reference is too noisy to hold the fast mode to 10%";
    EXPECT_LE(e.mean, 0.10) << "fast / reference " << e.ratio;
    EXPECT_LE(e.p90, 0.25) << "fast / reference " << e.ratio;
}

std::string sunName(const ::testing::TestParamInfo<std::string>& where) { return where.param; }

INSTANTIATE_TEST_SUITE_P(Sun, FastModeAccuracy, ::testing::Values("front", "beside", "behind"),
                         sunName);

}  // namespace

}  // namespace cg
