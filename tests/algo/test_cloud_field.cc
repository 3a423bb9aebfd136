// A field of clouds seen from above (algo/volume/CloudRegions.h, SizeDensity.h,
// CloudTracking.h): regions counted exactly, a power law's exponent recovered from samples of
// it, and clouds that drift, die, split and are born tracked to the exact counts.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>

#include "algo/volume/CloudTracking.h"
#include "algo/volume/SizeDensity.h"

namespace cg::algo {

namespace {

/// A width x height mask with the given discs (centre x, centre y, radius) set.
struct Disc {
    int x, y, r;
};
Mask2D discs(int width, int height, const std::vector<Disc>& list)
{
    Mask2D m;
    m.width = width;
    m.height = height;
    m.set.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0);
    for (const Disc& d : list)
        for (int y = d.y - d.r; y <= d.y + d.r; ++y)
            for (int x = d.x - d.r; x <= d.x + d.r; ++x)
                if ((x - d.x) * (x - d.x) + (y - d.y) * (y - d.y) <= d.r * d.r && x >= 0 &&
                    y >= 0 && x < width && y < height)
                    m.set[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                          static_cast<std::size_t>(x)] = 1;
    return m;
}

CoverFrame frame(int x0, int y0, const std::vector<Disc>& list)
{
    return {x0, y0, labelRegions(discs(120, 100, list))};
}

}  // namespace

TEST(CloudRegions, CountsEachRegionsAreaAndPerimeterExactly)
{
    // A 3 x 2 block, a lone pixel touching it only at a corner (4-connected: separate), and
    // an L of three pixels.
    Mask2D m;
    m.width = 8;
    m.height = 4;
    m.set = {1, 1, 1, 0, 0, 0, 1, 0,  //
             1, 1, 1, 0, 0, 0, 1, 1,  //
             0, 0, 0, 1, 0, 0, 0, 0,  //
             0, 0, 0, 0, 0, 0, 0, 0};
    const Regions r = labelRegions(m);
    ASSERT_EQ(r.area.size(), 3u);
    EXPECT_EQ(r.area[0], 6.0);
    EXPECT_EQ(r.perimeter[0], 10.0);
    EXPECT_EQ(r.area[1], 3.0);  // the L, met second in row order
    EXPECT_EQ(r.perimeter[1], 8.0);
    EXPECT_EQ(r.area[2], 1.0);
    EXPECT_EQ(r.perimeter[2], 4.0);
    EXPECT_EQ(r.at(3, 2), 2);
    EXPECT_EQ(r.at(7, 1), 1);
    EXPECT_EQ(r.at(4, 0), -1);
    EXPECT_EQ(r.at(-1, 0), -1);
}

TEST(SizeDensity, BinsCountEverySizeOnceAndDensitiesAreCountsOverWidths)
{
    const SizeDensityFit fit =
        fitSizeDensity({1.0, 1.5, 1.99, 2.0, 3.9, 4.0, 7.0, 0.5}, 1.0, 2.0, 1);
    ASSERT_EQ(fit.bins.size(), 3u);
    EXPECT_EQ(fit.bins[0].count, 3u);  // 1, 1.5, 1.99; 0.5 is below the smallest size
    EXPECT_EQ(fit.bins[1].count, 2u);
    EXPECT_EQ(fit.bins[2].count, 2u);
    EXPECT_DOUBLE_EQ(fit.bins[2].lo, 4.0);
    EXPECT_DOUBLE_EQ(fit.bins[2].density, 2.0 / 4.0);
    EXPECT_EQ(fit.fittedBins, 3u);
    EXPECT_THROW(fitSizeDensity({1.0}, 0.0, 2.0, 1), std::invalid_argument);
    EXPECT_THROW(fitSizeDensity({1.0}, 1.0, 1.0, 1), std::invalid_argument);
}

TEST(SizeDensity, RecoversThePowerLawSamplesWereDrawnFrom)
{
    // n(l) ~ l^b between 50 and 6400 m, drawn by inverting its cumulative distribution.
    std::mt19937 engine(7);
    for (const double b : {-1.7, -2.0, -2.5}) {
        const double lo = 50, hi = 6400, a = b + 1;  // hi on a bin edge
        std::vector<double> sizes;
        for (int i = 0; i < 20000; ++i) {
            const double u = (static_cast<double>(engine()) + 0.5) / 4294967296.0;
            sizes.push_back(
                std::pow(std::pow(lo, a) + u * (std::pow(hi, a) - std::pow(lo, a)), 1.0 / a));
        }
        const SizeDensityFit fit = fitSizeDensity(sizes, lo, std::sqrt(2.0), 24);
        EXPECT_GE(fit.fittedBins, 8u);
        EXPECT_NEAR(fit.exponent, b, 0.08) << "drawn with b = " << b;
    }
    // Too few clouds for three bins: no exponent.
    EXPECT_TRUE(std::isnan(fitSizeDensity({60, 61, 90, 91}, 50, 2.0, 2).exponent));
}

TEST(CloudTracking, FindsTheDriftAndCountsCloudsGoneAndBorn)
{
    // Five clouds drift by (+3, -2) columns a frame; by the third frame one has died (A) and
    // one has been born (F); one has split in two (C), which is not a death.
    const std::vector<Disc> start = {
        {10, 50, 4}, {30, 50, 5}, {50, 50, 6}, {70, 50, 4}, {90, 30, 3}};
    std::vector<CoverFrame> frames;
    frames.push_back(frame(0, 0, start));
    std::vector<Disc> mid = start;
    for (Disc& d : mid) d.x += 3, d.y -= 2;
    frames.push_back(frame(0, 0, mid));
    std::vector<Disc> end = {{36, 46, 5}, {52, 46, 3}, {60, 46, 2},
                             {76, 46, 4}, {96, 26, 3}, {20, 80, 5}};
    // The third frame's grid starts 10 columns further along x: positions are absolute.
    for (Disc& d : end) d.x -= 10;
    frames.push_back(frame(10, 0, end));
    const Turnover t = trackTurnover(frames, 8, 4);
    ASSERT_EQ(t.drifts.size(), 2u);
    EXPECT_EQ(t.drifts[0].dx, 3);
    EXPECT_EQ(t.drifts[0].dy, -2);
    EXPECT_EQ(t.drifts[1].dx, 3);
    EXPECT_EQ(t.drifts[1].dy, -2);
    EXPECT_EQ(t.firstClouds, 5u);
    EXPECT_EQ(t.lastClouds, 6u);
    EXPECT_EQ(t.gone, 1u);  // the cloud at x 10
    EXPECT_EQ(t.born, 1u);  // the cloud at (20, 80)
    EXPECT_THROW(trackTurnover({frames[0]}, 8, 4), std::invalid_argument);
}

TEST(CloudTracking, ACloudTooSmallToCountStillCarriesItsLineage)
{
    // A cloud shrinks below the counted size in the middle frame and grows back: it lives on.
    std::vector<CoverFrame> frames = {frame(0, 0, {{40, 40, 6}}), frame(0, 0, {{40, 40, 0}}),
                                      frame(0, 0, {{40, 40, 6}})};
    const Turnover t = trackTurnover(frames, 0, 4);
    EXPECT_EQ(t.gone, 0u);
    EXPECT_EQ(t.born, 0u);
}

TEST(CloudTracking, CoverOfAGridLabelsColumnsOfOpticalDepthAtLeastOneAndMeasuresTheirShare)
{
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(10.0));
    // 10 m voxels, extinction 0.01 /m: tau 0.1 a voxel. Eleven voxels deep: tau 1.1, a
    // cloud; nine: not.
    grid->denseFill(openvdb::CoordBBox({5, 5, 0}, {9, 9, 10}), 1.0f, true);
    grid->denseFill(openvdb::CoordBBox({20, 5, 0}, {24, 9, 8}), 1.0f, true);
    grid->denseFill(openvdb::CoordBBox({30, 7, 0}, {31, 8, 10}), 1.0f, true);
    const CoverFrame f = coverOf(topOpticalDepth(*grid, 0.01));
    EXPECT_EQ(f.x0, 5);
    EXPECT_EQ(f.y0, 5);
    ASSERT_EQ(f.regions.area.size(), 2u);
    EXPECT_EQ(f.regions.area[0], 25.0);
    EXPECT_EQ(f.regions.area[1], 4.0);
    EXPECT_EQ(f.regions.at(20 - 5, 5 - 5), -1);
    // Cover by column centres: the first cloud fills [50, 100)^2 m; both are 29 columns of
    // 100 m^2 in the 400 m square, and the 200 m square holds the first one's 25.
    EXPECT_DOUBLE_EQ(coverShare(f, 10.0, 50, 50, 100, 100), 1.0);
    EXPECT_DOUBLE_EQ(coverShare(f, 10.0, 0, 0, 400, 400), 29.0 * 100.0 / 160000.0);
    EXPECT_DOUBLE_EQ(coverShare(f, 10.0, 0, 0, 200, 200), 25.0 * 100.0 / 40000.0);
    EXPECT_EQ(coverShare(f, 10.0, 0, 0, 0, 200), 0.0);
}

}  // namespace cg::algo
