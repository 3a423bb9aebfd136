// The fast renderer's multiple-scattering solve (algo/render/RenderDiffusion.h).

#include <cmath>

#include <gtest/gtest.h>

#include "algo/render/RenderDiffusion.h"
#include "algo/render/RenderLightMap.h"
#include "algo/render/RenderOccupancy.h"
#include "support/RenderTestVolumes.h"

namespace cg {
namespace {

using algo::RenderDiffusion;
using algo::RenderVec3;

constexpr double kFourPi = 4.0 * 3.14159265358979323846;

struct LitBall {
    openvdb::FloatGrid::Ptr grid = test::makeBall(10.0, 16, 1.0f);
    algo::RenderMedium medium;
    algo::RenderOccupancy occupancy{grid->tree()};
    algo::RenderLightMap sunMap{*grid, occupancy, RenderVec3(0.3, 0.2, 1.0), 0.05, 1.0, 0.5};

    RenderDiffusion solve(bool shadowedGround)
    {
        medium.extinction = 0.05;
        return RenderDiffusion(*grid, sunMap, medium, 2, shadowedGround);
    }
};

TEST(RenderDiffusion, SkyAndGroundTogetherAreTheUniformSurroundings)
{
    // The problems are linear in what enters at the surface, and every surface face sees sky
    // and ground in shares that add up to one: a unit radiance of both together is uniform
    // surroundings of fluence 4π, which a conservative cloud holds everywhere unchanged.
    LitBall ball;
    ball.medium.albedo = 1.0;
    const RenderDiffusion d = ball.solve(true);
    ASSERT_FALSE(d.empty());
    for (const double z : {-120.0, -60.0, 0.0, 60.0, 120.0}) {
        const RenderDiffusion::Fluence f = d.at(RenderVec3(0.0, 0.0, z));
        EXPECT_NEAR(f.phi[RenderDiffusion::Sky] + f.phi[RenderDiffusion::Ground], kFourPi,
                    2e-3 * kFourPi)
            << "z = " << z;
    }
    // Sky light enters from above and ground light from below.
    const RenderDiffusion::Fluence top = d.at(RenderVec3(0, 0, 120));
    const RenderDiffusion::Fluence bottom = d.at(RenderVec3(0, 0, -120));
    EXPECT_GT(top.phi[RenderDiffusion::Sky], 1.5 * bottom.phi[RenderDiffusion::Sky]);
    EXPECT_GT(bottom.phi[RenderDiffusion::Ground], 1.5 * top.phi[RenderDiffusion::Ground]);
    EXPECT_LT(top.flux[RenderDiffusion::Sky].z(), 0.0);  // net flow downward
    EXPECT_GT(bottom.flux[RenderDiffusion::Ground].z(), 0.0);
}

TEST(RenderDiffusion, TheCloudsShadowDimsTheLitGroundItSees)
{
    // The sun-lit ground's light reaches the cloud only from ground outside its shadow: less
    // than the whole ground's, and nothing at all when no ground is lit.
    LitBall ball;
    ball.medium.albedo = 1.0;
    const RenderDiffusion lit = ball.solve(true);
    const RenderDiffusion::Fluence f = lit.at(RenderVec3(0, 0, -120));
    EXPECT_GT(f.phi[RenderDiffusion::LitGround], 0.0);
    EXPECT_LT(f.phi[RenderDiffusion::LitGround], f.phi[RenderDiffusion::Ground]);
    const RenderDiffusion unlit = ball.solve(false);
    EXPECT_EQ(unlit.at(RenderVec3(0, 0, -120)).phi[RenderDiffusion::LitGround], 0.0);
}

TEST(RenderDiffusion, SunLightScatteredOnceIsCarriedOnAlongTheSun)
{
    // A forward-peaked phase function carries scattered sun light on along the sun's way:
    // the net flux at the centre points with the sun's travel (down and away from it).
    LitBall ball;
    ball.medium.albedo = 1.0;
    const RenderDiffusion d = ball.solve(false);
    const RenderVec3 flux = d.at(RenderVec3(0, 0, 0)).flux[RenderDiffusion::Sun];
    const RenderVec3 travel = -RenderVec3(0.3, 0.2, 1.0).unitSafe();
    EXPECT_GT(flux.unitSafe().dot(travel), 0.9);
    // Light lit once near the sunny side fills the far side too.
    EXPECT_GT(d.at(-travel * -120.0).phi[RenderDiffusion::Sun], 0.0);
}

}  // namespace
}  // namespace cg
