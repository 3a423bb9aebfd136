// Box-counting dimensions against shapes whose dimension is known in closed form: a circle's
// outline (1), a filled disc (2), the Sierpinski carpet (log 8 / log 3) and the Koch
// snowflake's outline (log 4 / log 3), drawn as a curve and as the region it bounds.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "algo/volume/OutlineDimension.h"

namespace cg::algo {
namespace {

Mask2D emptyMask(int size)
{
    return {size, size, std::vector<std::uint8_t>(static_cast<std::size_t>(size) * size, 0)};
}

void setPixel(Mask2D& m, int x, int y)
{
    if (x >= 0 && y >= 0 && x < m.width && y < m.height)
        m.set[static_cast<std::size_t>(y) * m.width + x] = 1;
}

TEST(OutlineDimension, ASmoothOutlineIsOneDimensional)
{
    Mask2D disc = emptyMask(1024);
    for (int y = 0; y < 1024; ++y)
        for (int x = 0; x < 1024; ++x)
            if (std::hypot(x - 511.5, y - 511.5) < 450) setPixel(disc, x, y);
    EXPECT_NEAR(outlineDimension(disc, 4, 128), 1.0, 0.03);
    // The filled disc itself is two-dimensional.
    EXPECT_NEAR(boxCountingDimension(disc, 2, 64), 2.0, 0.05);
}

TEST(OutlineDimension, TheSierpinskiCarpetHasItsClosedFormDimension)
{
    const int size = 729;  // 3^6
    Mask2D carpet = emptyMask(size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            bool hole = false;
            for (int a = x, b = y; a > 0 || b > 0; a /= 3, b /= 3)
                hole = hole || (a % 3 == 1 && b % 3 == 1);
            if (!hole) setPixel(carpet, x, y);
        }
    // Boxes of 3^k align with the carpet's own cells: 1, 3, ... would be exact; powers of two
    // straddle them, so the estimate is within a few hundredths.
    EXPECT_NEAR(boxCountingDimension(carpet, 2, 128), std::log(8.0) / std::log(3.0), 0.05);
}

using Point = std::pair<double, double>;

/// The vertices of the Koch snowflake at `levels` subdivisions in a size x size square, the
/// first repeated at the end.
std::vector<Point> kochVertices(int size, int levels)
{
    const double r = size * 0.38, cx = size / 2.0, cy = size / 2.0;
    std::vector<Point> points;
    for (int k = 0; k < 3; ++k) {
        const double a = M_PI / 2 + k * 2 * M_PI / 3;
        points.push_back({cx + r * std::cos(a), cy + r * std::sin(a)});
    }
    points.push_back(points.front());
    for (int level = 0; level < levels; ++level) {
        std::vector<Point> next;
        for (std::size_t i = 0; i + 1 < points.size(); ++i) {
            const auto [x0, y0] = points[i];
            const auto [x1, y1] = points[i + 1];
            const double dx = (x1 - x0) / 3, dy = (y1 - y0) / 3;
            const Point a{x0 + dx, y0 + dy}, b{x0 + 2 * dx, y0 + 2 * dy};
            // The peak: the middle third turned outward by 60 degrees.
            const Point peak{a.first + dx * 0.5 + dy * std::sqrt(3.0) / 2,
                             a.second + dy * 0.5 - dx * std::sqrt(3.0) / 2};
            next.insert(next.end(), {points[i], a, peak, b});
        }
        next.push_back(points.back());
        points = std::move(next);
    }
    return points;
}

/// The Koch snowflake's outline drawn as a curve of pixels.
Mask2D kochSnowflake(int size, int levels)
{
    const std::vector<Point> points = kochVertices(size, levels);
    Mask2D m = emptyMask(size);
    for (std::size_t i = 0; i + 1 < points.size(); ++i) {
        const auto [x0, y0] = points[i];
        const auto [x1, y1] = points[i + 1];
        const int steps = static_cast<int>(std::ceil(std::hypot(x1 - x0, y1 - y0) * 2)) + 1;
        for (int t = 0; t <= steps; ++t)
            setPixel(m, static_cast<int>(x0 + (x1 - x0) * t / steps),
                     static_cast<int>(y0 + (y1 - y0) * t / steps));
    }
    return m;
}

/// The inside of the snowflake, filled exactly: pixel centres between crossings of each row.
Mask2D kochRegion(int size, int levels)
{
    const std::vector<Point> points = kochVertices(size, levels);
    Mask2D m = emptyMask(size);
    for (int y = 0; y < size; ++y) {
        const double cy = y + 0.5;
        std::vector<double> crossings;
        for (std::size_t i = 0; i + 1 < points.size(); ++i) {
            const auto [x0, y0] = points[i];
            const auto [x1, y1] = points[i + 1];
            if ((y0 <= cy) != (y1 <= cy))
                crossings.push_back(x0 + (cy - y0) * (x1 - x0) / (y1 - y0));
        }
        std::sort(crossings.begin(), crossings.end());
        for (std::size_t k = 0; k + 1 < crossings.size(); k += 2)
            for (int x = static_cast<int>(std::ceil(crossings[k] - 0.5));
                 x + 0.5 < crossings[k + 1]; ++x)
                setPixel(m, x, y);
    }
    return m;
}

TEST(OutlineDimension, TheKochSnowflakesOutlineHasItsClosedFormDimension)
{
    // As the region a cloud's silhouette is: the boxes its outline crosses.
    EXPECT_NEAR(outlineDimension(kochRegion(2048, 6), 4, 128), std::log(4.0) / std::log(3.0), 0.03);
    // As a curve of pixels.

    // 7 levels on 2048 pixels: the smallest segment (about 1.4 px) is below the smallest box.
    EXPECT_NEAR(boxCountingDimension(kochSnowflake(2048, 7), 4, 128), std::log(4.0) / std::log(3.0),
                0.06);
}

TEST(OutlineDimension, FewerThanThreeScalesOrAnEmptyMaskAreRefused)
{
    Mask2D m = emptyMask(64);
    EXPECT_THROW(boxCountingDimension(m, 2, 16), std::invalid_argument);
    EXPECT_THROW(outlineDimension(m, 2, 16), std::invalid_argument);  // no outline
    setPixel(m, 3, 3);
    EXPECT_THROW(boxCountingDimension(m, 0, 16), std::invalid_argument);
    EXPECT_THROW(boxCountingDimension(m, 4, 8), std::invalid_argument);
    EXPECT_NEAR(boxCountingDimension(m, 1, 16), 0.0, 1e-12);  // a point
}

}  // namespace
}  // namespace cg::algo
