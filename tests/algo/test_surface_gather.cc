// What surface faces and the ground see through the clear air
// (algo/render/lighting/SurfaceGather.h).

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "algo/render/lighting/SurfaceGather.h"

namespace cg {
namespace {

using algo::GatheredView;
using algo::GatherFace;
using algo::GatherGround;
using algo::GatherLattice;
using algo::RenderVec3;

constexpr double kFourPi = 4.0 * 3.14159265358979323846;
constexpr int kUnits = GatherLattice::kUnits;

/// A cube of n^3 cells of 10 m, clear air everywhere, axis-aligned with the world, its
/// lowest cells' centres 100 m above the ground.
GatherLattice clearLattice(int n)
{
    GatherLattice L;
    for (int a = 0; a < 3; ++a) L.n[a] = n;
    L.cellsPerMetre = openvdb::Mat3d::identity() * 0.1;
    L.origin = RenderVec3(0.0, 0.0, 100.0);
    for (int f = 0; f < 6; ++f) {
        L.normal[f] = RenderVec3(0.0);
        L.normal[f][f / 2] = f % 2 ? 1.0 : -1.0;
    }
    return L;
}

/// A cell of cloud of extinction `sigma` whose scattered light of unit `unit` is an
/// isotropic radiance `J` (albedo 1: a fluence 4π J and no net flux).
GatherLattice::Cloud glowing(const GatherLattice& L, int i, int j, int k, double sigma, int unit,
                             double J)
{
    GatherLattice::Cloud c;
    c.cell = L.cell(i, j, k);
    c.extinction = static_cast<float>(sigma);
    c.phi[unit] = static_cast<float>(kFourPi * J);
    return c;
}

/// A ground under the whole lattice and 200 m beyond it, its points 10 m apart.
GatherGround groundUnder(const GatherLattice& L)
{
    GatherGround g;
    g.present = true;
    g.map.min[0] = g.map.min[1] = -200.0;
    g.map.spacing = 10.0;
    g.map.n[0] = g.map.n[1] = 10 * L.n[0] / 10 + 41;
    return g;
}

TEST(SurfaceGather, ClearAirSeesTheOpenSkyAndNoCloudLight)
{
    const GatherLattice L = clearLattice(8);
    const std::vector<GatherFace> faces = {{{4, 4, 4}, 5}, {{4, 4, 4}, 0}, {{0, 0, 0}, 4}};
    GatherGround ground = groundUnder(L);
    ground.sunlit = [](const RenderVec3&) { return 0.25; };
    for (int stride : {1, 2}) {
        const algo::Gathered g = algo::gatherSurfaceLight(L, faces, ground, 16, 1.0, stride);
        for (std::size_t f = 0; f < faces.size(); ++f) {
            const GatheredView& v = g.faces[f];
            for (int side = 0; side < 2; ++side) {
                EXPECT_NEAR(v.transmittance[side], 1.0, 1e-6);
                for (int l = 0; l < kUnits; ++l) EXPECT_EQ(v.emitted[side][l], 0.0);
            }
            if (faces[f].kind == 5) continue;  // an upper face does not look down
            // Looking down, the open ground: its whole sky light, the sun's share.
            EXPECT_NEAR(v.ground[GatheredView::SkyLit], 1.0, 1e-6);
            EXPECT_NEAR(v.ground[GatheredView::SunLit], 0.25, 1e-6);
            for (int l = 0; l < kUnits; ++l) EXPECT_EQ(v.ground[GatheredView::Glow + l], 0.0);
        }
        ASSERT_EQ(g.ground.size(), ground.map.points());
        for (const algo::GroundView& p : g.ground) EXPECT_NEAR(p.sky, 1.0, 1e-6);
    }
}

TEST(SurfaceGather, AUniformGlowKeepsTheWhiteFurnace)
{
    // Every cell glows with J = 1 (unit 1) and attenuates: along every direction what the
    // clouds send plus what they let through is 1, so T + E = 1 wherever a face looks, and
    // wherever the ground looks up.
    GatherLattice L = clearLattice(12);
    for (int i = 0; i < 12; ++i)
        for (int j = 0; j < 12; ++j)
            for (int k = 0; k < 12; ++k) {
                const double sigma = 0.004 + 0.002 * double(L.cell(i, j, k) % 7);  // uneven
                if (k != 6) L.clouds.push_back(glowing(L, i, j, k, sigma, 1, 1.0));
            }
    const std::vector<GatherFace> faces = {{{6, 6, 6}, 5}, {{3, 8, 6}, 1}, {{6, 6, 6}, 4}};
    GatherGround ground = groundUnder(L);
    ground.smoothing = 30.0;  // the blur is linear: it keeps the furnace too
    const algo::Gathered g = algo::gatherSurfaceLight(L, faces, ground, 32, 1.0, 1);
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const GatheredView& v = g.faces[f];
        for (int side = 0; side < 2; ++side)
            EXPECT_NEAR(v.transmittance[side] + v.emitted[side][1], 1.0, 1e-5);
        // Below the horizon the ground, itself in the furnace, sends back 1 per unit of what
        // the face lets through to it: sky it sees plus the cloud's glow.
        if (faces[f].kind != 5) {
            EXPECT_NEAR(v.ground[GatheredView::SkyLit] + v.ground[GatheredView::Glow + 1],
                        v.transmittance[1], 1e-5);
        }
    }
    for (const algo::GroundView& p : g.ground) EXPECT_NEAR(p.sky + p.emitted[1], 1.0, 1e-5);
    // The medium is in the way wherever a face looks, and above the ground under it.
    EXPECT_LT(g.faces[0].transmittance[0], 0.95);
    EXPECT_LT(g.faces[1].transmittance[1], 0.95);
    EXPECT_LT(g.faces[2].transmittance[1], 0.95);
    EXPECT_LT(g.ground[groundUnder(L).map.n[0] * 26 + 26].sky, 0.95);
}

TEST(SurfaceGather, ASlabOverheadShadesTheSkyByItsOpticalDepth)
{
    // A horizontal slab, 2 cells (20 m) thick, of σ = 0.05 /m, 3 cells above a face looking
    // up: along a direction at cos θ from the zenith it lets through exp(−τ / cos θ), τ = 1;
    // below the horizon nothing is in the way.
    GatherLattice L = clearLattice(40);
    for (int i = 0; i < 40; ++i)
        for (int j = 0; j < 40; ++j)
            for (int k = 30; k < 32; ++k) L.clouds.push_back(glowing(L, i, j, k, 0.05, 0, 0.0));
    const std::vector<GatherFace> faces = {{{20, 20, 27}, 5}, {{20, 20, 27}, 1}};
    const std::vector<GatheredView> v =
        algo::gatherSurfaceLight(L, faces, GatherGround{}, 64, 1.0, 1).faces;
    // Looking up: the cosine-weighted mean of exp(−1/μ) over a hemisphere is 2 E_3(1) = 0.219
    // for an infinite slab; this one reaches 20 cells to each side, so only directions more
    // than 81° from the zenith pass beside it (about 2% of the cosine weight).
    EXPECT_NEAR(v[0].transmittance[0], 0.219 + 0.02, 0.04);
    EXPECT_NEAR(v[0].transmittance[1], 1.0, 1e-6);
    // Looking sideways (+y) sees the slab only in its upper directions.
    EXPECT_GT(v[1].transmittance[0], v[0].transmittance[0]);
    EXPECT_LT(v[1].transmittance[0], 1.0);
    EXPECT_NEAR(v[1].transmittance[1], 1.0, 1e-6);
}

TEST(SurfaceGather, LightFlowingDownShinesBrighterBelowThanAbove)
{
    // A thin slab whose light flows down (net flux F = −φ/2 ẑ, as out of a cloud's base lit
    // from above) and whose sun beam travels down: seen from below it is brighter than from
    // above, by the lobe's forward shape; with no flux and no beam, the same both ways.
    GatherLattice L = clearLattice(20);
    L.split = algo::DeltaEddington{0.5, 0.6};
    for (const bool flowing : {false, true}) {
        L.clouds.clear();
        for (int i = 0; i < 20; ++i)
            for (int j = 0; j < 20; ++j) {
                GatherLattice::Cloud c = glowing(L, i, j, 10, 0.01, 0, 1.0);
                if (flowing) {
                    c.flux[0][2] = -0.5f * c.phi[0];
                    c.beam = 0.5f;
                }
                L.clouds.push_back(c);
            }
        const std::vector<GatherFace> faces = {{{10, 10, 5}, 5}, {{10, 10, 15}, 4}};
        const std::vector<GatheredView> v =
            algo::gatherSurfaceLight(L, faces, GatherGround{}, 64, 1.0, 1).faces;
        const double below = v[0].emitted[0][0], above = v[1].emitted[1][0];
        EXPECT_GT(below, 0.0);
        if (flowing)
            EXPECT_GT(below, 1.5 * above);
        else  // the same but for the sweep's interpolation
            EXPECT_NEAR(below, above, 0.05 * above);
    }
}

TEST(SurfaceGather, TheGroundUnderACloudSeesLessSkyAndItsGlow)
{
    // A glowing layer 160 m wide, 115 m above the ground: the ground right under it sees
    // less of the sky than the ground far from it, and the layer's light; a face of the layer
    // looking down sees that shaded ground.
    GatherLattice L = clearLattice(16);
    for (int i = 0; i < 16; ++i)
        for (int j = 0; j < 16; ++j)
            for (int k = 2; k < 6; ++k) L.clouds.push_back(glowing(L, i, j, k, 0.05, 2, 0.5));
    const GatherGround ground = groundUnder(L);
    const std::vector<GatherFace> faces = {{{8, 8, 1}, 4}};
    const algo::Gathered g = algo::gatherSurfaceLight(L, faces, ground, 64, 1.0, 1);
    std::size_t at[4];
    double w[4];
    ASSERT_TRUE(ground.map.corners(RenderVec3(75.0, 75.0, 0.0), at, w));
    const algo::GroundView& under = g.ground[at[0]];
    ASSERT_TRUE(ground.map.corners(RenderVec3(-190.0, -190.0, 0.0), at, w));
    const algo::GroundView& far = g.ground[at[0]];
    EXPECT_LT(under.sky, 0.8 * far.sky);
    EXPECT_GT(under.emitted[2], 2.0 * far.emitted[2]);
    // What the layer lets through plus twice its glow (J = 1/2) is 1 along every direction.
    EXPECT_NEAR(under.sky + 2.0 * under.emitted[2], 1.0, 1e-4);
    const GatheredView& base = g.faces[0];
    EXPECT_LT(base.ground[GatheredView::SkyLit], 0.9);
    EXPECT_GT(base.ground[GatheredView::Glow + 2], 0.0);
}

TEST(SurfaceGather, ASmallCloudAsideIsSeenAsLargeAsItIsWhereverTheDirectionsFall)
{
    // A thick glowing ball (J = 1, radius 6 cells) 22 cells in front of a face looking
    // along +y, moved sideways by 0 to 8 cells: the face should gather J times the ball's
    // share of its cosine-weighted view (computed here on a fine grid of directions). 32 directions
    // as bare rays meet so small a ball with a few or none; the sweeps' spread makes each a cone,
    // so the share holds better at every offset.
    constexpr int kN = 48;
    constexpr double kRadius = 6.0;
    const RenderVec3 face(24.0, 8.5, 24.0);  // the air cell's face toward +y, in cells
    double lowest = 1e9, highest = 0.0;
    for (int offset = 0; offset <= 8; offset += 2) {
        GatherLattice L = clearLattice(kN);
        const RenderVec3 centre(24.0 + offset, 30.0, 24.0);
        for (int i = 0; i < kN; ++i)
            for (int j = 0; j < kN; ++j)
                for (int k = 0; k < kN; ++k)
                    if ((RenderVec3(i, j, k) - centre).length() <= kRadius)
                        L.clouds.push_back(glowing(L, i, j, k, 1.0, 1, 1.0));
        const GatheredView v =
            algo::gatherSurfaceLight(L, {{{24, 8, 24}, 3}}, GatherGround{}, 32, 1.0, 1).faces[0];
        // A horizontal normal: half the cosine weight above the horizon, half below.
        const double seen = 0.5 * (v.emitted[0][1] + v.emitted[1][1]);
        // The exact share: cosine-weighted directions about +y on a fine grid (sin²θ and
        // the azimuth uniform), each tested against the ball.
        const RenderVec3 to = centre - face;
        double share = 0.0;
        constexpr int kRings = 400, kAzimuths = 400;
        for (int r = 0; r < kRings; ++r)
            for (int a = 0; a < kAzimuths; ++a) {
                const double sin2 = (r + 0.5) / kRings, sinT = std::sqrt(sin2);
                const double phi = 2.0 * 3.14159265358979323846 * (a + 0.5) / kAzimuths;
                const RenderVec3 d(sinT * std::cos(phi), std::sqrt(1.0 - sin2),
                                   sinT * std::sin(phi));
                const double along = to.dot(d);
                if (along > 0.0 && (to - d * along).length() <= kRadius + 0.5) share += 1.0;
            }
        share /= kRings * kAzimuths;
        lowest = std::min(lowest, seen / share);
        highest = std::max(highest, seen / share);
    }
    // With the spread 0.80-1.12 of the share; bare rays gave 0.70-1.27.
    EXPECT_GT(lowest, 0.75);
    EXPECT_LT(highest, 1.2);
    EXPECT_LT(highest - lowest, 0.4);
}

}  // namespace
}  // namespace cg
