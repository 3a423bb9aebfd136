// The fast renderer's multiple-scattering solve (algo/render/lighting/RenderDiffusion.h).

#include <cmath>

#include <gtest/gtest.h>

#include "algo/render/lighting/RenderDiffusion.h"
#include "algo/render/lighting/RenderLightMap.h"
#include "algo/render/media/RenderOccupancy.h"
#include "support/RenderTestVolumes.h"

namespace cg {
namespace {

using algo::RenderDiffusion;
using algo::RenderVec3;

constexpr double kFourPi = 4.0 * 3.14159265358979323846;

/// Light `which` alone, of unit radiance in every channel.
algo::DiffuseLight alone(const RenderDiffusion& d, RenderDiffusion::Light which)
{
    RenderVec3 radiance[RenderDiffusion::kLights];
    for (RenderVec3& r : radiance) r = RenderVec3(0.0);
    radiance[which] = RenderVec3(1.0);
    return d.coloured(radiance);
}

struct LitBall {
    openvdb::FloatGrid::Ptr grid = test::makeBall(10.0, 16, 1.0f);
    algo::RenderMedium medium;
    algo::RenderOccupancy occupancy{grid->tree()};
    algo::RenderLightMap sunMap{*grid, occupancy, RenderVec3(0.3, 0.2, 1.0), 0.05, 1.0, 0.5};

    RenderDiffusion solve(RenderDiffusion::GroundPlane ground)
    {
        medium.extinction = 0.05;
        return RenderDiffusion(*grid, sunMap, medium, 2, ground);
    }
};

TEST(RenderDiffusion, SkyAndGroundTogetherAreTheUniformSurroundings)
{
    // The problems are linear in what enters at the surface, and every surface face sees sky
    // and ground in shares that add up to one: a unit radiance of both together is uniform
    // surroundings of fluence 4π, which a conservative cloud holds everywhere unchanged.
    // Sky in the red channel and ground in the green one add up the same way.
    LitBall ball;
    ball.medium.albedo = 1.0;
    const RenderDiffusion d = ball.solve({false, false});
    ASSERT_FALSE(d.empty());
    const algo::DiffuseLight split =
        d.coloured({RenderVec3(0.0), RenderVec3(1, 0, 0), RenderVec3(0, 1, 0), RenderVec3(0.0),
                    RenderVec3(0.0), RenderVec3(0.0)});
    for (const double z : {-120.0, -60.0, 0.0, 60.0, 120.0}) {
        const algo::DiffuseLight::Sample f = split.at(RenderVec3(0.0, 0.0, z));
        EXPECT_NEAR(f.phi[0] + f.phi[1], kFourPi, 2e-3 * kFourPi) << "z = " << z;
        EXPECT_NEAR(f.phi[2], 0.0, 1e-6) << "z = " << z;
    }
    // Sky light enters from above and ground light from below.
    const algo::DiffuseLight sky = alone(d, RenderDiffusion::Sky);
    const algo::DiffuseLight ground = alone(d, RenderDiffusion::Ground);
    const RenderVec3 top(0, 0, 120), bottom(0, 0, -120);
    EXPECT_GT(sky.at(top).phi[0], 1.5 * sky.at(bottom).phi[0]);
    EXPECT_GT(ground.at(bottom).phi[0], 1.5 * ground.at(top).phi[0]);
    EXPECT_LT(sky.at(top).flux[0].z(), 0.0);  // net flow downward
    EXPECT_GT(ground.at(bottom).flux[0].z(), 0.0);
    // Outside the lattice: the surroundings' fluence, channel by channel.
    const algo::DiffuseLight::Sample far = split.at(RenderVec3(0, 0, 5000));
    EXPECT_DOUBLE_EQ(far.phi[0], 0.5 * kFourPi);
    EXPECT_DOUBLE_EQ(far.phi[1], 0.5 * kFourPi);
    EXPECT_EQ(far.flux[0], RenderVec3(0.0));
}

TEST(RenderDiffusion, TheCloudsShadowDimsTheLitGroundItSees)
{
    // The sun-lit ground's light reaches the cloud only from ground outside its shadow: less
    // than a whole open ground's, and nothing at all when no ground is lit.
    LitBall ball;
    ball.medium.albedo = 1.0;
    const RenderDiffusion lit = ball.solve({true, true});
    const RenderVec3 bottom(0, 0, -120);
    const double litGround = alone(lit, RenderDiffusion::LitGround).at(bottom).phi[0];
    EXPECT_GT(litGround, 0.0);
    const RenderDiffusion open = ball.solve({false, false});
    EXPECT_LT(litGround, alone(open, RenderDiffusion::Ground).at(bottom).phi[0]);
    const RenderDiffusion unlit = ball.solve({true, false});
    EXPECT_EQ(alone(unlit, RenderDiffusion::LitGround).at(bottom).phi[0], 0.0);
}

TEST(RenderDiffusion, SunLightScatteredOnceIsCarriedOnAlongTheSun)
{
    // A forward-peaked phase function carries scattered sun light on along the sun's way:
    // the net flux at the centre points with the sun's travel (down and away from it).
    LitBall ball;
    ball.medium.albedo = 1.0;
    const algo::DiffuseLight sun = alone(ball.solve({false, false}), RenderDiffusion::Sun);
    const RenderVec3 flux = sun.at(RenderVec3(0, 0, 0)).flux[0];
    const RenderVec3 travel = -RenderVec3(0.3, 0.2, 1.0).unitSafe();
    EXPECT_GT(flux.unitSafe().dot(travel), 0.9);
    // Light lit once near the sunny side fills the far side too.
    EXPECT_GT(sun.at(-travel * -120.0).phi[0], 0.0);
}

TEST(RenderDiffusion, WithoutASunNoSunLightIsScattered)
{
    // A render without a sun has no sun light map: the solve scatters no sun light (the
    // flux limiter then comes from the sky's fluence), while the sky still lights the cloud.
    LitBall ball;
    ball.medium.extinction = 0.05;
    const algo::RenderLightMap noSun;
    const RenderDiffusion d(*ball.grid, noSun, ball.medium, 2, {false, false});
    ASSERT_FALSE(d.empty());
    const algo::DiffuseLight sun = alone(d, RenderDiffusion::Sun);
    const algo::DiffuseLight sky = alone(d, RenderDiffusion::Sky);
    for (const double z : {-120.0, 0.0, 120.0}) {
        EXPECT_EQ(sun.at(RenderVec3(0.0, 0.0, z)).phi[0], 0.0) << "z = " << z;
        EXPECT_GT(sky.at(RenderVec3(0.0, 0.0, z)).phi[0], 0.0) << "z = " << z;
    }
}

}  // namespace
}  // namespace cg
