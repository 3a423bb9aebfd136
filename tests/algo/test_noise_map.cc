// The 1/f^beta density map: spectrum slope, range, determinism, sizes, centre bias.

#include <gtest/gtest.h>

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

#include "algo/atmosphere/NoiseMap.h"

namespace cg {

namespace {

algo::NoiseMapSettings settings(int nx, int ny, double beta, std::uint64_t seed)
{
    algo::NoiseMapSettings s;
    s.nx = nx;
    s.ny = ny;
    s.beta = beta;
    s.seed = seed;
    return s;
}

/// Log-log slope of the radially averaged power spectrum, averaged over `seeds` maps.
/// Radial bins are rings of width 1 / min(nx, ny) cycles per cell (the integer radii of a
/// square map); each bin holds the mean of log f and of log P over its coefficients and
/// seeds (log P of a noisy coefficient has a constant bias, which leaves the slope alone).
/// The DC bin and f > 0.4 cycles per cell are excluded; the fit is ordinary least squares.
double spectrumSlope(int nx, int ny, double beta, int seeds)
{
    const auto w = static_cast<std::size_t>(nx);
    const auto h = static_cast<std::size_t>(ny);
    const std::size_t wc = w / 2 + 1;
    std::vector<double> real(w * h);
    std::vector<fftw_complex> spec(h * wc);
    fftw_plan plan = fftw_plan_dft_r2c_2d(ny, nx, real.data(), spec.data(), FFTW_ESTIMATE);

    const double df = 1.0 / std::min(nx, ny);
    struct Bin {
        double sumLogF = 0.0;
        double sumLogP = 0.0;
        double count = 0.0;
    };
    std::map<long, Bin> bins;
    for (int seed = 0; seed < seeds; ++seed) {
        const std::vector<float> map =
            algo::noiseMap(settings(nx, ny, beta, static_cast<std::uint64_t>(seed) + 11));
        std::copy(map.begin(), map.end(), real.begin());
        fftw_execute(plan);
        for (std::size_t j = 0; j < h; ++j) {
            const double fy = ((2 * j <= h) ? double(j) : double(j) - double(h)) / double(h);
            for (std::size_t i = 0; i < wc; ++i) {
                const double fx = double(i) / double(w);
                const double f = std::hypot(fx, fy);
                const long bin = std::lround(f / df);
                if (bin == 0 || f > 0.4) continue;
                const fftw_complex& c = spec[j * wc + i];
                const double p = c[0] * c[0] + c[1] * c[1];
                Bin& b = bins[bin];
                b.sumLogF += std::log(f);
                b.sumLogP += std::log(p);
                b.count += 1.0;
            }
        }
    }
    fftw_destroy_plan(plan);

    double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
    for (const auto& [k, b] : bins) {
        const double x = b.sumLogF / b.count;
        const double y = b.sumLogP / b.count;
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
        n += 1.0;
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

void expectUnitRange(const std::vector<float>& v)
{
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    EXPECT_EQ(*lo, 0.0f);
    EXPECT_EQ(*hi, 1.0f);
}

}  // namespace

TEST(NoiseMap, SpectrumSlopeIsMinusBeta)
{
    for (double beta : {2.0, 2.7, 3.0, 3.3}) {
        const double slope = spectrumSlope(256, 256, beta, 3);
        EXPECT_NEAR(slope, -beta, 0.1) << "beta " << beta;
    }
}

TEST(NoiseMap, NonSquareSpectrumIsIsotropicInCells)
{
    EXPECT_NEAR(spectrumSlope(300, 125, 3.0, 4), -3.0, 0.1);
}

TEST(NoiseMap, ValuesSpanExactlyZeroToOne)
{
    for (double beta : {0.0, 2.7, 3.3, 6.0})
        expectUnitRange(algo::noiseMap(settings(64, 64, beta, 3)));
    expectUnitRange(algo::noiseMap(settings(2, 1, 3.0, 0)));
    expectUnitRange(algo::noiseMap(settings(1, 7, 3.0, 0)));
}

TEST(NoiseMap, OneCellIsConstantHalf)
{
    EXPECT_EQ(algo::noiseMap(settings(1, 1, 3.0, 5)), std::vector<float>{0.5f});
    algo::NoiseMapSettings s = settings(1, 1, 3.0, 5);
    s.centreBias = 1.0;
    EXPECT_EQ(algo::noiseMap(s), std::vector<float>{0.5f});
}

TEST(NoiseMap, SameSeedSameMapOtherSeedOtherMap)
{
    const auto a = algo::noiseMap(settings(96, 80, 3.0, 42));
    const auto b = algo::noiseMap(settings(96, 80, 3.0, 42));
    const auto c = algo::noiseMap(settings(96, 80, 3.0, 43));
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
    EXPECT_NE(a, c);
}

TEST(NoiseMap, NonSquareSizes)
{
    for (auto [nx, ny] : {std::pair{300, 125}, std::pair{150, 100}, std::pair{64, 64},
                          std::pair{200, 100}, std::pair{125, 300}, std::pair{1, 64}}) {
        const auto v = algo::noiseMap(settings(nx, ny, 3.0, 1));
        ASSERT_EQ(v.size(), static_cast<std::size_t>(nx * ny)) << nx << "x" << ny;
        expectUnitRange(v);
    }
}

TEST(NoiseMap, CentreBiasRaisesTheCentre)
{
    const int n = 64;
    for (std::uint64_t seed = 0; seed < 5; ++seed) {
        algo::NoiseMapSettings s = settings(n, n, 3.0, seed);
        s.centreBias = 1.0;
        const auto v = algo::noiseMap(s);
        expectUnitRange(v);
        double centre = 0, border = 0, nc = 0, nb = 0;
        for (int iy = 0; iy < n; ++iy) {
            for (int ix = 0; ix < n; ++ix) {
                const float x = v[static_cast<std::size_t>(iy * n + ix)];
                if (ix >= 16 && ix < 48 && iy >= 16 && iy < 48) {
                    centre += x;
                    nc += 1;
                } else if (ix < 8 || ix >= 56 || iy < 8 || iy >= 56) {
                    border += x;
                    nb += 1;
                }
            }
        }
        EXPECT_GT(centre / nc, border / nb) << "seed " << seed;
    }
}

TEST(NoiseMap, ZeroBiasIsThePlainMap)
{
    const auto plain = algo::noiseMap(settings(80, 60, 2.7, 9));
    algo::NoiseMapSettings s = settings(80, 60, 2.7, 9);
    s.centreBias = 0.0;
    s.centreRadius = 3.0;  // irrelevant without bias
    EXPECT_EQ(algo::noiseMap(s), plain);
    s.centreBias = 0.5;
    EXPECT_NE(algo::noiseMap(s), plain);
}

/// The share of a map's power (mean removed) at frequencies under fCut cycles per cell.
double powerShareBelow(const std::vector<float>& map, int nx, int ny, double fCut)
{
    const auto w = static_cast<std::size_t>(nx);
    const auto h = static_cast<std::size_t>(ny);
    const std::size_t wc = w / 2 + 1;
    std::vector<double> real(map.begin(), map.end());
    std::vector<fftw_complex> spec(h * wc);
    fftw_plan plan = fftw_plan_dft_r2c_2d(ny, nx, real.data(), spec.data(), FFTW_ESTIMATE);
    fftw_execute(plan);
    fftw_destroy_plan(plan);
    double below = 0.0, total = 0.0;
    for (std::size_t j = 0; j < h; ++j) {
        const double fy = ((2 * j <= h) ? double(j) : double(j) - double(h)) / double(h);
        for (std::size_t i = 0; i < wc; ++i) {
            const double f = std::hypot(double(i) / double(w), fy);
            if (f == 0.0) continue;
            const double p = spec[j * wc + i][0] * spec[j * wc + i][0] +
                             spec[j * wc + i][1] * spec[j * wc + i][1];
            total += p;
            if (f < fCut) below += p;
        }
    }
    return below / total;
}

TEST(NoiseMap, LargestWavelengthRemovesTheLongerScalesOnly)
{
    algo::NoiseMapSettings s = settings(128, 96, 4.0, 5);
    const auto plain = algo::noiseMap(s);
    // A 1/f^4 map keeps most of its power in its longest waves.
    EXPECT_GT(powerShareBelow(plain, 128, 96, 1.0 / 24.0), 0.5);
    s.largestWavelength = 24.0;
    const auto cut = algo::noiseMap(s);
    expectUnitRange(cut);
    // What is left down there is the float rounding of the output.
    EXPECT_LT(powerShareBelow(cut, 128, 96, 1.0 / 24.0), 1e-9);
    EXPECT_GT(powerShareBelow(cut, 128, 96, 1.0 / 20.0), 0.01);
    // 0 is the paper's map, and a wavelength longer than the map removes nothing either.
    s.largestWavelength = 0.0;
    EXPECT_EQ(algo::noiseMap(s), plain);
    s.largestWavelength = 200.0;
    EXPECT_EQ(algo::noiseMap(s), plain);
}

TEST(NoiseMap, BadSettingsAreRefused)
{
    EXPECT_THROW(algo::noiseMap(settings(0, 4, 3.0, 0)), std::invalid_argument);
    EXPECT_THROW(algo::noiseMap(settings(4, -1, 3.0, 0)), std::invalid_argument);
    EXPECT_THROW(algo::noiseMap(settings(4, 4, -1.0, 0)), std::invalid_argument);
    EXPECT_THROW(algo::noiseMap(settings(4, 4, NAN, 0)), std::invalid_argument);
    algo::NoiseMapSettings s = settings(4, 4, 3.0, 0);
    s.centreBias = 1.5;
    EXPECT_THROW(algo::noiseMap(s), std::invalid_argument);
    s.centreBias = 0.5;
    s.centreRadius = 0.0;
    EXPECT_THROW(algo::noiseMap(s), std::invalid_argument);
    s.centreRadius = 0.5;
    s.largestWavelength = -1.0;
    EXPECT_THROW(algo::noiseMap(s), std::invalid_argument);
}

TEST(NoiseMap, CancellationPropagates)
{
    int calls = 0;
    const auto cancel = [&calls] {
        if (++calls == 3) throw std::runtime_error("stop");
    };
    EXPECT_THROW(algo::noiseMap(settings(128, 128, 3.0, 0), cancel), std::runtime_error);
    EXPECT_EQ(calls, 3);
    // The planner lock was released: the next map works.
    EXPECT_EQ(algo::noiseMap(settings(8, 8, 3.0, 0)).size(), 64u);
}

}  // namespace cg
