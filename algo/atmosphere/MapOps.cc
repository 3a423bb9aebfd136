#include "algo/atmosphere/MapOps.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cg::algo {

namespace {

float unit(double v) { return static_cast<float>(std::clamp(v, 0.0, 1.0)); }

double smoothstep(double edge0, double edge1, double x)
{
    const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

/// One pass of a normalised Gaussian along x (stride 1) or y (stride nx), the taps that fall
/// off the map left out and the rest renormalised, so an edge is not darkened.
std::vector<float> blurPass(const GroundMap& m, const std::vector<float>& in, bool alongX,
                            const std::vector<double>& taps)
{
    const int reach = static_cast<int>(taps.size()) - 1;
    std::vector<float> out(in.size());
    for (int iy = 0; iy < m.ny; ++iy)
        for (int ix = 0; ix < m.nx; ++ix) {
            double sum = 0.0, weight = 0.0;
            for (int d = -reach; d <= reach; ++d) {
                const int x = alongX ? ix + d : ix, y = alongX ? iy : iy + d;
                if (x < 0 || y < 0 || x >= m.nx || y >= m.ny) continue;
                const double w = taps[static_cast<std::size_t>(std::abs(d))];
                sum += w * in[static_cast<std::size_t>(y) * m.nx + x];
                weight += w;
            }
            out[static_cast<std::size_t>(iy) * m.nx + ix] = static_cast<float>(sum / weight);
        }
    return out;
}

std::vector<float> blur(const GroundMap& m, double radius)
{
    const double sigma = radius / m.cell;  // cells
    if (!(sigma > 0.0)) return m.values;
    // Taps past the map's far edge never land on it.
    const double wanted = std::ceil(3.0 * sigma);
    const int reach = static_cast<int>(std::max(1.0, std::min(wanted, std::max(m.nx, m.ny) - 1.0)));
    if (reach > 512)
        throw std::invalid_argument(
            "MapMath: blurRadius reaches more than 512 cells of this map (at most 170 cells)");
    std::vector<double> taps(static_cast<std::size_t>(reach) + 1);
    for (int d = 0; d <= reach; ++d)
        taps[static_cast<std::size_t>(d)] = std::exp(-0.5 * d * d / (sigma * sigma));
    return blurPass(m, blurPass(m, m.values, true, taps), false, taps);
}

}  // namespace

MapOp mapOpFromName(const std::string& name)
{
    static const std::pair<const char*, MapOp> kNames[] = {{"multiply", MapOp::Multiply},
                                                           {"add", MapOp::Add},
                                                           {"subtract", MapOp::Subtract},
                                                           {"min", MapOp::Min},
                                                           {"max", MapOp::Max},
                                                           {"invert", MapOp::Invert},
                                                           {"threshold", MapOp::Threshold},
                                                           {"blur", MapOp::Blur},
                                                           {"remap", MapOp::Remap}};
    for (const auto& [n, op] : kNames)
        if (name == n) return op;
    throw std::invalid_argument("unknown map operation '" + name + "'");
}

bool mapOpIsBinary(MapOp op)
{
    return op == MapOp::Multiply || op == MapOp::Add || op == MapOp::Subtract || op == MapOp::Min ||
           op == MapOp::Max;
}

float sampleGroundMap(const GroundMap& b, double x, double y)
{
    // Cell centres at (i + 0.5) cell.
    const double gx = std::clamp(x / b.cell - 0.5, 0.0, b.nx - 1.0);
    const double gy = std::clamp(y / b.cell - 0.5, 0.0, b.ny - 1.0);
    const int x0 = static_cast<int>(std::floor(gx)), y0 = static_cast<int>(std::floor(gy));
    const int x1 = std::min(x0 + 1, b.nx - 1), y1 = std::min(y0 + 1, b.ny - 1);
    const double tx = gx - x0, ty = gy - y0;
    const auto at = [&b](int i, int j) {
        return static_cast<double>(b.values[static_cast<std::size_t>(j) * b.nx + i]);
    };
    const double v = (at(x0, y0) * (1 - tx) + at(x1, y0) * tx) * (1 - ty) +
                     (at(x0, y1) * (1 - tx) + at(x1, y1) * tx) * ty;
    return static_cast<float>(v);
}

GroundMap applyMapOp(const GroundMap& a, const GroundMap* b, const MapOpSettings& s)
{
    if (mapOpIsBinary(s.op) && !b)
        throw std::invalid_argument("MapMath: the operation needs map b");
    if (s.op == MapOp::Remap && !(s.high > s.low))
        throw std::invalid_argument("MapMath: remap needs high > low");
    if (s.op == MapOp::Remap && !(s.gamma > 0.0))
        throw std::invalid_argument("MapMath: gamma must be > 0");
    GroundMap out = a;
    if (s.op == MapOp::Blur) {
        out.values = blur(a, s.blurRadius);
        return out;
    }
    for (int iy = 0; iy < a.ny; ++iy)
        for (int ix = 0; ix < a.nx; ++ix) {
            const std::size_t i = static_cast<std::size_t>(iy) * a.nx + ix;
            const double v = a.values[i];
            const double w =
                b ? sampleGroundMap(*b, (ix + 0.5) * a.cell, (iy + 0.5) * a.cell) : 0.0;
            double r = v;
            switch (s.op) {
                case MapOp::Multiply:
                    r = v * w;
                    break;
                case MapOp::Add:
                    r = v + w;
                    break;
                case MapOp::Subtract:
                    r = v - w;
                    break;
                case MapOp::Min:
                    r = std::min(v, w);
                    break;
                case MapOp::Max:
                    r = std::max(v, w);
                    break;
                case MapOp::Invert:
                    r = 1.0 - v;
                    break;
                case MapOp::Threshold:
                    r = s.softness > 0.0 ? smoothstep(s.threshold - 0.5 * s.softness,
                                                      s.threshold + 0.5 * s.softness, v)
                                         : (v >= s.threshold ? 1.0 : 0.0);
                    break;
                case MapOp::Remap:
                    r = std::pow(std::clamp((v - s.low) / (s.high - s.low), 0.0, 1.0), s.gamma);
                    break;
                case MapOp::Blur:
                    break;
            }
            out.values[i] = unit(r);
        }
    return out;
}

}  // namespace cg::algo
