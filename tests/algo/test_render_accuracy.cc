// The fast mode against the reference path tracer on a small cumulus (the synthetic cloud of
// graphs/cumulus_still.json at half its resolution), with the sun in front of the camera,
// beside it and behind it: the fast mode's mean relative luminance error over the cloud's
// pixels must stay within 10% and its 90th percentile within 25%, issue 16's goal.
// bench/render_error measures the same on larger volumes (docs/rendering.md).

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "algo/render/RenderError.h"
#include "algo/render/RenderPathTrace.h"
#include "algo/render/RenderVolume.h"
#include "algo/render/SyntheticCumulus.h"

namespace cg {

namespace {

using algo::RenderVec3;

constexpr int kWidth = 64, kHeight = 48;
constexpr int kReferenceSamples = 1024;  // per half, two halves with independent seeds

struct Scene {
    openvdb::FloatGrid::Ptr grid;
    algo::RenderSettings s;
};

Scene smallCumulus()
{
    algo::SyntheticCumulusSettings c;
    c.seed = 3;
    c.voxelSize = 20.0;
    c.baseHeight = 900.0;
    c.baseRadius = 700.0;
    c.towerHeight = 1.3;
    Scene out;
    out.grid = algo::rasterizeCumulus(algo::cumulusBlobs(c), c);
    out.s.camera.position = RenderVec3(400, -3800, 700);
    out.s.camera.lookAt = RenderVec3(0, 0, 1200);
    out.s.camera.fovDegrees = 40.0;
    out.s.camera.width = kWidth;
    out.s.camera.height = kHeight;
    out.s.medium.extinction = 0.05;
    out.s.pathTrace.samples = kReferenceSamples;
    return out;
}

class FastModeAccuracy : public ::testing::TestWithParam<std::string> {};

TEST_P(FastModeAccuracy, StaysWithinTenPercentOfThePathTracer)
{
    Scene scene = smallCumulus();
    scene.s.sun.direction = algo::sunAroundCamera(scene.s.camera, GetParam());
    const algo::RenderedImage fast = algo::renderFogVolume(*scene.grid, scene.s);
    algo::RenderedImage half[2];
    for (int i = 0; i < 2; ++i) {
        algo::RenderSettings h = scene.s;
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
