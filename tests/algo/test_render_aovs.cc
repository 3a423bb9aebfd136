// The fast renderer's AOVs: the sun and sky parts of the cloud's light are what a render by
// the sun alone and by the sky alone give (to the diffusion's nonlinearity), and they sum
// to the cloud layer; asking for them
// leaves the beauty bit for bit; the depth of a uniform slab is its closed-form
// opacity-weighted mean; the ground's shadow matte under a slab is 1 − its sun transmittance.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "algo/render/image/CloudLayer.h"
#include "algo/render/integrators/RenderVolume.h"
#include "algo/render/media/Phase.h"
#include "support/RenderTestVolumes.h"

namespace cg {

namespace {

using algo::RenderVec3;

/// A ball over the ground, lit from the side and above, seen from below its middle.
algo::RenderSettings ballScene(algo::MultiScatterModel model)
{
    algo::RenderSettings s;
    s.camera.position = RenderVec3(0, -1800, 150);
    s.camera.lookAt = RenderVec3(0, 0, 300);
    s.camera.fovDegrees = 35.0;
    s.camera.width = 48;
    s.camera.height = 36;
    s.sun.direction = RenderVec3(0.8, 0.2, 0.5);
    s.medium.extinction = 0.03;
    s.multiScatter.model = model;
    return s;
}

std::vector<float> cloudOf(const algo::RenderedImage& img)
{
    return algo::cloudLayer(img.rgba, img.background);
}

float largest(const std::vector<float>& v)
{
    float m = 0.0f;
    for (float x : v) m = std::max(m, std::abs(x));
    return m;
}

class RenderAovs : public ::testing::TestWithParam<algo::MultiScatterModel> {};

}  // namespace

TEST_P(RenderAovs, SunAndSkyAreTheRendersByEachLightAloneAndSumToTheCloud)
{
    auto grid = test::makeBall(10.0, 20, 1.0f);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(10.0));
    // Lift the ball 300 m off the ground.
    grid->transform().postTranslate(openvdb::Vec3d(0, 0, 300));
    algo::RenderSettings s = ballScene(GetParam());
    const algo::RenderedImage plain = algo::renderFogVolume(*grid, s);
    s.aovs = true;
    const algo::RenderedImage img = algo::renderFogVolume(*grid, s);
    EXPECT_EQ(img.rgba, plain.rgba);  // the beauty is untouched
    EXPECT_TRUE(plain.sun.empty());
    ASSERT_EQ(img.sun.size(), 3u * 48 * 36);

    algo::RenderSettings sunOnly = s, skyOnly = s;
    // The same light maps and solves, one light black.
    sunOnly.sky.zenith = sunOnly.sky.horizon = RenderVec3(0.0);
    skyOnly.sun.colour = RenderVec3(0.0);
    const std::vector<float> bySun = cloudOf(algo::renderFogVolume(*grid, sunOnly));
    const std::vector<float> bySky = cloudOf(algo::renderFogVolume(*grid, skyOnly));
    const std::vector<float> cloud = cloudOf(img);
    const float scale = largest(cloud);
    ASSERT_GT(scale, 0.0f);
    // The octaves' light is linear in the lights: each part is its light's render. The
    // diffusion's is not quite (a lobe of mean cosine |F| / φ, DiffuseLight.h): where sun and
    // sky light cross, the parts share the total in the proportion of each light's own lobe,
    // within 4% of the brightest pixel of each light's render (measured 3.5%), and 1% overall.
    const bool linear = GetParam() == algo::MultiScatterModel::Octaves;
    const float near = (linear ? 1e-4f : 0.04f) * scale;
    double sunTotal = 0.0, skyTotal = 0.0, bySunTotal = 0.0, bySkyTotal = 0.0;
    for (std::size_t p = 0; p < 48 * 36; ++p)
        for (int c = 0; c < 3; ++c) {
            const std::size_t i = 3 * p + static_cast<std::size_t>(c), j = 4 * p + c;
            EXPECT_NEAR(img.sun[i] + img.sky[i], cloud[j], 2e-5f * scale) << p;
            EXPECT_NEAR(img.sun[i], bySun[j], near) << p;
            EXPECT_NEAR(img.sky[i], bySky[j], near) << p;
            sunTotal += img.sun[i];
            skyTotal += img.sky[i];
            bySunTotal += bySun[j];
            bySkyTotal += bySky[j];
        }
    EXPECT_NEAR(sunTotal / bySunTotal, 1.0, linear ? 1e-5 : 0.01);
    EXPECT_NEAR(skyTotal / bySkyTotal, 1.0, linear ? 1e-5 : 0.01);
    // Both lights matter in this scene: neither part is empty.
    EXPECT_GT(sunTotal, 0.05 * (sunTotal + skyTotal));
    EXPECT_GT(skyTotal, 0.05 * (sunTotal + skyTotal));
}

INSTANTIATE_TEST_SUITE_P(Models, RenderAovs,
                         ::testing::Values(algo::MultiScatterModel::Diffusion,
                                           algo::MultiScatterModel::Octaves));

TEST(RenderAovsDepth, AUniformSlabHasItsOpacityWeightedMeanDepth)
{
    // A slab of voxels y = 0..39 at 2 m (y in [-1, 79] m with a one-voxel ramp at each face:
    // the plateau 0..78 m), seen head on from 500 m: the depth where the light is made,
    // weighted by what each sample adds to the opacity, is y0 + 1/σ − L e^{−σL} / (1 − e^{−σL})
    // from the camera for a uniform σ over [y0, y0 + L].
    const double voxel = 2.0;
    auto slab = test::makeBox(voxel, openvdb::Coord(-30, 0, -30), openvdb::Coord(30, 39, 30), 1.0f);
    algo::RenderSettings s;
    s.camera.position = RenderVec3(0, -500, 0);
    s.camera.lookAt = RenderVec3(0, 0, 0);
    s.camera.fovDegrees = 10.0;
    s.camera.width = 9;
    s.camera.height = 9;
    s.ground.enabled = false;
    s.multiScatter.model = algo::MultiScatterModel::Octaves;  // no diffusion solve to wait for
    s.medium.extinction = 0.04;
    s.march.step = 0.25;
    s.aovs = true;
    const algo::RenderedImage img = algo::renderFogVolume(*slab, s);
    const double sigma = 0.04, y0 = 500.0 - 1.0, L = 80.0;
    // The ramps make the slab's density trilinear at its faces; a uniform slab of the same
    // optical depth between the voxel-centre planes is what the closed form describes.
    const double e = std::exp(-sigma * L);
    const double expected = y0 + 1.0 / sigma - L * e / (1.0 - e);
    const float centre = img.depth[4 * 9 + 4];
    EXPECT_NEAR(centre, expected, 1.5) << "closed form " << expected;

    // Seen from the side, the sky behind: no depth.
    s.camera.lookAt = RenderVec3(0, -500, 1000);
    s.camera.up = RenderVec3(0, 1, 0);
    const algo::RenderedImage sky = algo::renderFogVolume(*slab, s);
    EXPECT_EQ(sky.depth[4 * 9 + 4], algo::kNoDepth);
}

TEST(RenderAovsShadow, TheMatteUnderASlabIsWhatItTakesFromTheSun)
{
    // A 200 m thick slab 1000-1200 m up, the sun at the zenith; the camera under it looks at
    // the ground below the slab's middle. The ground there loses exp(−(1 − ω f) σ 200) of the
    // direct sun (δ-Eddington, as the background is lit); the sky, none.
    const double voxel = 20.0;
    auto slab =
        test::makeBox(voxel, openvdb::Coord(-100, -100, 50), openvdb::Coord(100, 100, 59), 0.5f);
    algo::RenderSettings s;
    s.camera.position = RenderVec3(0, -600, 300);
    s.camera.lookAt = RenderVec3(0, 0, 0);
    s.camera.fovDegrees = 20.0;
    s.camera.width = 9;
    s.camera.height = 9;
    s.sun.direction = RenderVec3(0, 0, 1);
    s.medium.extinction = 0.01;
    s.aovs = true;
    const algo::RenderedImage img = algo::renderFogVolume(*slab, s);
    const double peak = algo::phaseOf(s.medium).deltaEddington().peak;
    const double tau = 0.01 * 0.5 * 200.0;
    const double expected = 1.0 - std::exp(-(1.0 - s.medium.albedo * peak) * tau);
    EXPECT_NEAR(img.shadow[4 * 9 + 4], expected, 0.02 * expected);
    EXPECT_EQ(img.rgba[(4 * 9 + 4) * 4 + 3], 0.0f);  // the camera's ray misses the slab

    s.camera.lookAt = RenderVec3(0, 0, 2000);  // up through the slab at the sky
    const algo::RenderedImage up = algo::renderFogVolume(*slab, s);
    EXPECT_EQ(up.shadow[4 * 9 + 4], 0.0f);
}

}  // namespace cg
