// What surface faces see through the clear air (algo/render/SurfaceGather.h).

#include <cmath>

#include <gtest/gtest.h>

#include "algo/render/SurfaceGather.h"

namespace cg {
namespace {

using algo::GatheredView;
using algo::GatherFace;
using algo::GatherLattice;

/// A cube of n^3 cells of 10 m, clear air everywhere, axis-aligned with the world.
GatherLattice clearLattice(int n)
{
    GatherLattice L;
    for (int a = 0; a < 3; ++a) L.n[a] = n;
    L.extinction.assign(L.cells(), 0.0);
    L.source.assign(L.cells(), {0.0f, 0.0f, 0.0f, 0.0f});
    L.cellsPerMetre = openvdb::Mat3d::identity() * 0.1;
    for (int f = 0; f < 6; ++f) {
        L.normal[f] = algo::RenderVec3(0.0);
        L.normal[f][f / 2] = f % 2 ? 1.0 : -1.0;
    }
    return L;
}

TEST(SurfaceGather, ClearAirSeesTheOpenSkyAndNoCloudLight)
{
    const GatherLattice L = clearLattice(8);
    const std::vector<GatherFace> faces = {{{4, 4, 4}, 5}, {{4, 4, 4}, 0}, {{0, 0, 0}, 4}};
    for (int stride : {1, 2})
        for (const GatheredView& v : algo::gatherSurfaceLight(L, faces, 16, 1.0, stride)) {
            for (int side = 0; side < 2; ++side) {
                EXPECT_NEAR(v.transmittance[side], 1.0, 1e-6);
                for (int l = 0; l < GatherLattice::kUnits; ++l) EXPECT_EQ(v.emitted[side][l], 0.0);
            }
        }
}

TEST(SurfaceGather, AUniformGlowKeepsTheWhiteFurnace)
{
    // Every cell glows with J = 1 (unit 1) and attenuates: along every direction what the
    // clouds send plus what they let through is 1, so T + E = 1 wherever a face looks.
    GatherLattice L = clearLattice(12);
    for (std::size_t c = 0; c < L.extinction.size(); ++c) {
        L.extinction[c] = 0.004 + 0.002 * double(c % 7);  // 1/m, uneven
        L.source[c] = {0.0f, 1.0f, 0.0f, 0.0f};
    }
    const std::vector<GatherFace> faces = {{{6, 6, 6}, 5}, {{3, 8, 2}, 1}, {{6, 6, 10}, 4}};
    for (const GatheredView& v : algo::gatherSurfaceLight(L, faces, 32, 1.0, 1)) {
        for (int side = 0; side < 2; ++side)
            EXPECT_NEAR(v.transmittance[side] + v.emitted[side][1], 1.0, 1e-5);
    }
    // The medium is in the way wherever a face looks: above the first two, below the last.
    const std::vector<GatheredView> v = algo::gatherSurfaceLight(L, faces, 32, 1.0, 1);
    EXPECT_LT(v[0].transmittance[0], 0.95);
    EXPECT_LT(v[1].transmittance[0], 0.95);
    EXPECT_LT(v[1].transmittance[1], 0.95);
    EXPECT_LT(v[2].transmittance[1], 0.95);
}

TEST(SurfaceGather, ASlabOverheadShadesTheSkyByItsOpticalDepth)
{
    // A horizontal slab, 2 cells (20 m) thick, of σ = 0.05 /m, 3 cells above a face looking
    // up: along a direction at cos θ from the zenith it lets through exp(−τ / cos θ), τ = 1;
    // below the horizon nothing is in the way.
    GatherLattice L = clearLattice(40);
    for (int i = 0; i < 40; ++i)
        for (int j = 0; j < 40; ++j)
            for (int k = 30; k < 32; ++k) L.extinction[L.cell(i, j, k)] = 0.05;
    const std::vector<GatherFace> faces = {{{20, 20, 27}, 5}, {{20, 20, 27}, 1}};
    const std::vector<GatheredView> v = algo::gatherSurfaceLight(L, faces, 64, 1.0, 1);
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

}  // namespace
}  // namespace cg
