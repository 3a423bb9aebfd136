#include "algo/atmosphere/Outflow.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cg::algo {

namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
constexpr double kMaxCells = 4.0e6;

}  // namespace

std::vector<std::uint32_t> towerIds(const float* x0, const float* y0, std::size_t n,
                                    double cellSize)
{
    std::vector<std::uint32_t> ids(n, 0);
    if (n == 0) return ids;
    // Plain pointers, not structured bindings: C++17 lambdas cannot capture those.
    const auto rangeX = std::minmax_element(x0, x0 + n);
    const auto rangeY = std::minmax_element(y0, y0 + n);
    const float* minX = rangeX.first;
    const float* maxX = rangeX.second;
    const float* minY = rangeY.first;
    const float* maxY = rangeY.second;
    const double spanX = static_cast<double>(*maxX) - *minX;
    const double spanY = static_cast<double>(*maxY) - *minY;
    double cell = cellSize;
    while ((spanX / cell + 1.0) * (spanY / cell + 1.0) > kMaxCells) cell *= 2.0;
    const auto nx = static_cast<std::size_t>(spanX / cell) + 1;
    const auto ny = static_cast<std::size_t>(spanY / cell) + 1;
    const auto cellOf = [&](std::size_t i) {
        const auto ix = std::min(nx - 1, static_cast<std::size_t>((x0[i] - *minX) / cell));
        const auto iy = std::min(ny - 1, static_cast<std::size_t>((y0[i] - *minY) / cell));
        return iy * nx + ix;
    };
    // Label the occupied cells by flood fill, starting from particles in order.
    std::vector<std::uint32_t> label(nx * ny, kNone);
    std::vector<char> occupied(nx * ny, 0);
    for (std::size_t i = 0; i < n; ++i) occupied[cellOf(i)] = 1;
    std::uint32_t next = 0;
    std::vector<std::size_t> stack;
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t start = cellOf(i);
        if (label[start] == kNone) {
            label[start] = next;
            stack.push_back(start);
            while (!stack.empty()) {
                const std::size_t c = stack.back();
                stack.pop_back();
                const std::size_t cx = c % nx, cy = c / nx;
                for (std::size_t yy = cy > 0 ? cy - 1 : 0; yy <= std::min(ny - 1, cy + 1); ++yy)
                    for (std::size_t xx = cx > 0 ? cx - 1 : 0; xx <= std::min(nx - 1, cx + 1);
                         ++xx) {
                        const std::size_t k = yy * nx + xx;
                        if (occupied[k] && label[k] == kNone) {
                            label[k] = next;
                            stack.push_back(k);
                        }
                    }
            }
            ++next;
        }
        ids[i] = label[start];
    }
    return ids;
}

void towerAxes(const std::vector<std::uint32_t>& ids, const float* x, const float* y,
               const float* z, float bottom, std::vector<float>& axisX, std::vector<float>& axisY)
{
    const std::size_t n = ids.size();
    const std::uint32_t towers = n ? *std::max_element(ids.begin(), ids.end()) + 1 : 0;
    std::vector<double> sumX(towers, 0.0), sumY(towers, 0.0);
    std::vector<std::size_t> count(towers, 0);
    for (std::size_t i = 0; i < n; ++i)
        if (z[i] >= bottom) {
            sumX[ids[i]] += x[i];
            sumY[ids[i]] += y[i];
            ++count[ids[i]];
        }
    axisX.resize(n);
    axisY.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t c = count[ids[i]];
        axisX[i] = c ? static_cast<float>(sumX[ids[i]] / static_cast<double>(c)) : x[i];
        axisY[i] = c ? static_cast<float>(sumY[ids[i]] / static_cast<double>(c)) : y[i];
    }
}

}  // namespace cg::algo
