// ThermalField: diameters follow the truncated power law (closed-form inverse, a
// Kolmogorov-Smirnov test and a binned log-log slope like the metric), the field
// covers what it is asked to, disks never overlap, and the same seed gives the same field.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "algo/atmosphere/ThermalField.h"

namespace cg {

using algo::ThermalFieldSettings;

namespace {

double lawCdf(double l, double a, double c, double b)
{
    const double k = b + 1.0;
    return (std::pow(l, k) - std::pow(a, k)) / (std::pow(c, k) - std::pow(a, k));
}

/// A 20 km field of 50 m cells, as issue 54's cumulus day.
ThermalFieldSettings dayField()
{
    ThermalFieldSettings s;
    s.nx = s.ny = 400;
    s.cellSize = 50.0;
    return s;
}

}  // namespace

TEST(ThermalField, TheDiameterIsTheInverseOfTheLawsDistribution)
{
    for (double u : {0.0, 0.1, 0.5, 0.9, 0.999})
        EXPECT_NEAR(lawCdf(algo::powerLawDiameter(u, 200, 2000, -1.7), 200, 2000, -1.7), u, 1e-12);
    EXPECT_NEAR(algo::powerLawDiameter(0.0, 200, 2000, -2.3), 200.0, 1e-9);
    EXPECT_NEAR(algo::powerLawDiameter(1.0, 200, 2000, -2.3), 2000.0, 1e-9);
}

TEST(ThermalField, PlacedSizesFollowThePowerLaw)
{
    for (double b : {-1.7, -2.3}) {
        ThermalFieldSettings s = dayField();
        s.exponent = b;
        s.seed = 3;
        const algo::ThermalField f = algo::placeThermals(s);
        const std::size_t n = f.thermals.size();
        ASSERT_GE(n, 100u) << b;  // issue 54 asks >= 100 clouds over 20 km
        EXPECT_LE(f.leftOut, n / 100) << b;
        // Kolmogorov-Smirnov against the law: D below its 1% critical value.
        std::vector<double> l;
        for (const algo::Thermal& t : f.thermals) l.push_back(t.diameter);
        std::sort(l.begin(), l.end());
        double d = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            const double F = lawCdf(l[i], s.smallest, s.largest, b);
            d = std::max({d, F - double(i) / n, double(i + 1) / n - F});
        }
        EXPECT_LT(d, 1.63 / std::sqrt(double(n))) << b;
        // The metric: counts per unit size in logarithmic bins, a least-squares slope
        // in log-log over the bins holding >= 24 clouds, within 0.3 of b.
        const int bins = 6;
        std::vector<double> x, y;
        for (int k = 0; k < bins; ++k) {
            const double lo = s.smallest * std::pow(s.largest / s.smallest, double(k) / bins);
            const double hi = s.smallest * std::pow(s.largest / s.smallest, double(k + 1) / bins);
            const auto count =
                std::count_if(l.begin(), l.end(), [&](double v) { return v >= lo && v < hi; });
            if (count < 24) continue;
            x.push_back(std::log(std::sqrt(lo * hi)));
            y.push_back(std::log(double(count) / (hi - lo)));
        }
        ASSERT_GE(x.size(), 3u) << b;
        const double mx = std::accumulate(x.begin(), x.end(), 0.0) / x.size();
        const double my = std::accumulate(y.begin(), y.end(), 0.0) / y.size();
        double sxy = 0.0, sxx = 0.0;
        for (std::size_t i = 0; i < x.size(); ++i) {
            sxy += (x[i] - mx) * (y[i] - my);
            sxx += (x[i] - mx) * (x[i] - mx);
        }
        EXPECT_NEAR(sxy / sxx, b, 0.3) << b;
    }
}

TEST(ThermalField, TheFieldCoversWhatItIsAskedAndNoDisksOverlap)
{
    for (double cover : {0.1, 0.2, 0.3}) {
        ThermalFieldSettings s = dayField();
        s.cover = cover;
        const algo::ThermalField f = algo::placeThermals(s);
        const std::vector<float> map = algo::thermalMap(s, f);
        const auto cloudy =
            std::count_if(map.begin(), map.end(), [](float v) { return v >= 0.5f; });
        EXPECT_NEAR(double(cloudy) / map.size(), cover, 0.03) << cover;
        for (std::size_t i = 0; i < f.thermals.size(); ++i)
            for (std::size_t j = i + 1; j < f.thermals.size(); ++j) {
                const algo::Thermal &a = f.thermals[i], &c = f.thermals[j];
                const double ra = a.diameter / 1.5, rc = c.diameter / 1.5;
                ASSERT_GE(std::hypot(a.x - c.x, a.y - c.y), ra + rc + s.gap * std::max(ra, rc))
                    << i << " " << j;
            }
    }
}

TEST(ThermalField, TheSameSeedGivesTheSameFieldAndBadSettingsAreRefused)
{
    ThermalFieldSettings s = dayField();
    const algo::ThermalField a = algo::placeThermals(s), b = algo::placeThermals(s);
    ASSERT_EQ(a.thermals.size(), b.thermals.size());
    for (std::size_t i = 0; i < a.thermals.size(); ++i) {
        EXPECT_EQ(a.thermals[i].x, b.thermals[i].x);
        EXPECT_EQ(a.thermals[i].diameter, b.thermals[i].diameter);
    }
    s.seed = 1;
    EXPECT_NE(algo::placeThermals(s).thermals.front().x, a.thermals.front().x);

    const auto refused = [](ThermalFieldSettings bad, const char* what) {
        try {
            algo::checkThermalField(bad);
            ADD_FAILURE() << what << " accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
        }
    };
    ThermalFieldSettings bad = dayField();
    bad.exponent = -1.0;
    refused(bad, "exponent");
    bad = dayField();
    bad.largest = 100.0;
    refused(bad, "largest");
    bad = dayField();
    bad.cover = 0.7;
    refused(bad, "cover");
    bad = dayField();
    bad.nx = bad.ny = 65536;
    bad.smallest = bad.largest = 1.0;
    refused(bad, "thermals");  // billions of 1 m clouds: refused before any is drawn
}

}  // namespace cg

namespace cg::algo {

// The starts map: each thermal's disk holds one value of its own, drawn per thermal, and the
// ground between them 0, so wired as a start delay every cell of a thermal starts together.
TEST(ThermalField, EachThermalHasOneStartOverItsDiskAndTheGroundBetweenNone)
{
    ThermalFieldSettings s = dayField();
    s.nx = s.ny = 200;
    s.cellSize = 50.0;
    const ThermalField field = placeThermals(s);
    const std::vector<float> density = thermalMap(s, field);
    const std::vector<float> starts = thermalStartMap(s, field);
    ASSERT_EQ(starts.size(), density.size());
    std::vector<float> perThermal;
    for (const Thermal& t : field.thermals) {
        const int ix = static_cast<int>(t.x / s.cellSize), iy = static_cast<int>(t.y / s.cellSize);
        const float v = starts[static_cast<std::size_t>(iy) * 200 + static_cast<std::size_t>(ix)];
        EXPECT_GE(v, 0.0f);
        EXPECT_LT(v, 1.0f);
        // Every cell within half the thermal's diameter (where its density is 1) has its start.
        const double r = 0.3 * t.diameter;
        for (int jy = 0; jy < 200; ++jy)
            for (int jx = 0; jx < 200; ++jx)
                if (std::hypot((jx + 0.5) * s.cellSize - t.x, (jy + 0.5) * s.cellSize - t.y) < r) {
                    ASSERT_EQ(starts[static_cast<std::size_t>(jy) * 200 + jx], v);
                }
        perThermal.push_back(v);
    }
    for (std::size_t i = 0; i < density.size(); ++i)
        if (density[i] == 0.0f) {
            ASSERT_EQ(starts[i], 0.0f) << i;
        }
    // Uniform draws: their mean within 4 standard errors of 1/2.
    ASSERT_GT(perThermal.size(), 30u);
    double mean = 0.0;
    for (float v : perThermal) mean += v;
    mean /= static_cast<double>(perThermal.size());
    EXPECT_NEAR(mean, 0.5, 4.0 * std::sqrt(1.0 / 12.0 / static_cast<double>(perThermal.size())));
    EXPECT_EQ(thermalStartMap(s, placeThermals(s)), starts);
}

TEST(ThermalField, EachCellTakesTheCopyScaleOfItsNearestThermal)
{
    // A 1000 x 100 m map of 10 m cells: a thermal of 150 m (half the full scale of 300 m;
    // disk radius 100 m) at x 100 m and one of 600 m (full scale; radius 400 m) at x 700 m.
    ThermalFieldSettings s;
    s.nx = 100;
    s.ny = 10;
    s.cellSize = 10.0;
    s.fullScaleCloud = 300.0;
    ThermalField field;
    field.thermals = {{700.0, 50.0, 600.0}, {100.0, 50.0, 150.0}};
    const std::vector<float> scale = thermalScaleMap(s, field);
    ASSERT_EQ(scale.size(), 1000u);
    const auto at = [&](double x, double y) {
        return scale[static_cast<std::size_t>(y / 10.0) * 100 + static_cast<std::size_t>(x / 10.0)];
    };
    EXPECT_EQ(at(105, 55), 0.5f);  // on the small disk
    EXPECT_EQ(at(5, 5), 0.5f);     // off every disk, nearest the small one
    EXPECT_EQ(at(215, 55), 0.5f);  // between the disks, nearer the small one's edge
    EXPECT_EQ(at(285, 55), 1.0f);  // nearer the large one's
    EXPECT_EQ(at(705, 55), 1.0f);  // on the large disk
    for (const float v : scale) EXPECT_TRUE(v == 0.5f || v == 1.0f);
    // No thermals: every copy at full scale.
    EXPECT_EQ(thermalScaleMap(s, ThermalField{}), std::vector<float>(1000, 1.0f));
    s.fullScaleCloud = 0.0;
    EXPECT_THROW(checkThermalField(s), ThermalFieldError);
}

}  // namespace cg::algo
