#pragma once
/// A grid of points on the ground plane z = 0 (row by row, x first), and bilinear weights
/// at a point of the plane: the map on which the diffusion keeps what the ground sees above
/// it (SurfaceGather.h) and the renderer reads the ground's light (DiffuseLight.h).

#include <algorithm>
#include <cstddef>

#include "algo/render/RenderSettings.h"

namespace cg::algo {

struct GroundGrid {
    double min[2] = {0.0, 0.0};  ///< m, world x and y of point (0, 0)
    double spacing = 1.0;        ///< m between neighbouring points
    int n[2] = {0, 0};           ///< points along x and y

    std::size_t points() const
    {
        return static_cast<std::size_t>(n[0]) * static_cast<std::size_t>(n[1]);
    }
    RenderVec3 point(std::size_t at) const
    {
        const std::size_t row = at / static_cast<std::size_t>(n[0]);
        return {min[0] + spacing * double(at % static_cast<std::size_t>(n[0])),
                min[1] + spacing * double(row), 0.0};
    }

    /// The four points around p and their bilinear weights; false beyond the grid.
    bool corners(const RenderVec3& p, std::size_t (&at)[4], double (&weight)[4]) const
    {
        if (n[0] < 2 || n[1] < 2) return false;
        const double x = (p.x() - min[0]) / spacing, y = (p.y() - min[1]) / spacing;
        if (!(x >= 0.0 && y >= 0.0 && x <= n[0] - 1 && y <= n[1] - 1)) return false;
        const int i = std::min(static_cast<int>(x), n[0] - 2);
        const int j = std::min(static_cast<int>(y), n[1] - 2);
        const double fx = x - i, fy = y - j;
        for (int c = 0; c < 4; ++c) {
            const int di = c & 1, dj = c >> 1;
            at[c] = static_cast<std::size_t>(j + dj) * static_cast<std::size_t>(n[0]) +
                    static_cast<std::size_t>(i + di);
            weight[c] = (di ? fx : 1.0 - fx) * (dj ? fy : 1.0 - fy);
        }
        return true;
    }
};

}  // namespace cg::algo
