#include "algo/atmosphere/CloudColumn.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

namespace cg::algo {

CloudColumn cloudColumn(const float* x, const float* y, const float* z,
                        const std::int32_t* condensedFrame, std::size_t n, double binM,
                        double cellM)
{
    CloudColumn c;
    c.binM = binM;
    if (n == 0) return c;
    float minX = x[0], maxX = x[0], minY = y[0], maxY = y[0];
    for (std::size_t i = 0; i < n; ++i) {
        minX = std::min(minX, x[i]), maxX = std::max(maxX, x[i]);
        minY = std::min(minY, y[i]), maxY = std::max(maxY, y[i]);
        if (condensedFrame[i] < 0) continue;
        ++c.condensed;
        c.baseM = std::isnan(c.baseM) ? z[i] : std::min<double>(c.baseM, z[i]);
        c.topM = std::isnan(c.topM) ? z[i] : std::max<double>(c.topM, z[i]);
    }
    if (c.condensed == 0) return c;
    double cell = cellM;
    const double spanX = static_cast<double>(maxX) - minX, spanY = static_cast<double>(maxY) - minY;
    while ((spanX / cell + 1.0) * (spanY / cell + 1.0) > 4.0e6) cell *= 2.0;
    const auto nx = static_cast<std::uint64_t>(spanX / cell) + 1;
    const auto ny = static_cast<std::uint64_t>(spanY / cell) + 1;
    const auto bins = static_cast<std::size_t>(std::max(0.0, c.topM) / binM) + 1;
    // (bin, cell) pairs that hold a condensed particle; a set, as most of the grid is empty.
    std::unordered_set<std::uint64_t> occupied;
    for (std::size_t i = 0; i < n; ++i) {
        if (condensedFrame[i] < 0 || z[i] < 0.0f) continue;
        const auto bin = static_cast<std::uint64_t>(z[i] / binM);
        const auto ix = std::min(nx - 1, static_cast<std::uint64_t>((x[i] - minX) / cell));
        const auto iy = std::min(ny - 1, static_cast<std::uint64_t>((y[i] - minY) / cell));
        occupied.insert((bin * ny + iy) * nx + ix);
    }
    std::vector<std::uint64_t> count(bins, 0);
    for (std::uint64_t key : occupied) ++count[key / (nx * ny)];
    c.fraction.resize(bins);
    for (std::size_t k = 0; k < bins; ++k)
        c.fraction[k] = static_cast<double>(count[k]) / static_cast<double>(nx * ny);
    return c;
}

}  // namespace cg::algo
