#include "algo/volume/CloudTracking.h"

#include <algorithm>
#include <cstdint>
#include <stdexcept>

namespace cg::algo {

namespace {

/// The drift is searched on every kCoarseStride-th column first, then refined.
constexpr int kCoarseStride = 4;

/// The cloud index of `f` at absolute column (x, y), or -1.
std::int32_t labelAt(const CoverFrame& f, int x, int y) { return f.regions.at(x - f.x0, y - f.y0); }

/// For every pair of clouds (a of `from`, b of `to`) that share a column once `from` is
/// shifted by the drift: link[a] holds b.
std::vector<std::vector<std::int32_t>> links(const CoverFrame& from, const CoverFrame& to,
                                             const Drift& d)
{
    std::vector<std::vector<std::int32_t>> out(from.regions.area.size());
    for (int j = 0; j < from.regions.height; ++j)
        for (int i = 0; i < from.regions.width; ++i) {
            const std::int32_t a = from.regions.at(i, j);
            if (a < 0) continue;
            const std::int32_t b = labelAt(to, from.x0 + i + d.dx, from.y0 + j + d.dy);
            if (b < 0) continue;
            out[static_cast<std::size_t>(a)].push_back(b);
        }
    for (auto& l : out) {
        std::sort(l.begin(), l.end());
        l.erase(std::unique(l.begin(), l.end()), l.end());
    }
    return out;
}

std::size_t countLarge(const Regions& r, double minCells)
{
    std::size_t n = 0;
    for (const double a : r.area) n += a >= minCells ? 1 : 0;
    return n;
}

/// The columns of `from` on the lattice of every stride-th column that land on cloud of
/// `to` under the shift.
std::size_t overlapAt(const CoverFrame& from, const CoverFrame& to, int dx, int dy, int stride)
{
    std::size_t n = 0;
    for (int j = 0; j < from.regions.height; j += stride)
        for (int i = 0; i < from.regions.width; i += stride)
            if (from.regions.at(i, j) >= 0 && labelAt(to, from.x0 + i + dx, from.y0 + j + dy) >= 0)
                ++n;
    return n;
}

/// The shift within `reach` of (cx, cy) with the largest overlap, the first in scan order on
/// a tie.
Drift bestShift(const CoverFrame& from, const CoverFrame& to, int cx, int cy, int reach, int stride)
{
    Drift best{cx - reach, cy - reach, 0};
    bool first = true;
    for (int dy = cy - reach; dy <= cy + reach; ++dy)
        for (int dx = cx - reach; dx <= cx + reach; ++dx) {
            const std::size_t overlap = overlapAt(from, to, dx, dy, stride);
            if (first || overlap > best.overlap) best = {dx, dy, overlap};
            first = false;
        }
    return best;
}

}  // namespace

CoverFrame coverOf(const TopView& top)
{
    Mask2D m;
    m.width = top.width;
    m.height = top.height;
    m.set.resize(top.tau.size());
    for (std::size_t i = 0; i < top.tau.size(); ++i) m.set[i] = top.tau[i] >= 1.0 ? 1 : 0;
    return {top.x0, top.y0, labelRegions(m)};
}

double coverShare(const CoverFrame& f, double voxel, double x0, double y0, double x1, double y1)
{
    if (!(x1 > x0) || !(y1 > y0)) return 0.0;
    std::size_t inside = 0;
    for (int j = 0; j < f.regions.height; ++j)
        for (int i = 0; i < f.regions.width; ++i) {
            if (f.regions.at(i, j) < 0) continue;
            const double x = (f.x0 + i + 0.5) * voxel, y = (f.y0 + j + 0.5) * voxel;
            inside += x >= x0 && y >= y0 && x < x1 && y < y1 ? 1 : 0;
        }
    return static_cast<double>(inside) * voxel * voxel / ((x1 - x0) * (y1 - y0));
}

Drift estimateDrift(const CoverFrame& from, const CoverFrame& to, int maxShift)
{
    const Drift coarse = bestShift(from, to, 0, 0, maxShift, kCoarseStride);
    const int reach = std::min(maxShift, kCoarseStride - 1);
    return bestShift(from, to, coarse.dx, coarse.dy, reach, 1);
}

Turnover trackTurnover(const std::vector<CoverFrame>& frames, int maxShift, double minCells)
{
    if (frames.size() < 2) throw std::invalid_argument("trackTurnover: needs two frames or more");
    if (maxShift < 0) throw std::invalid_argument("trackTurnover: maxShift must be >= 0");
    Turnover t;
    std::vector<std::vector<std::vector<std::int32_t>>> step;  // step[k][a] = clouds of k+1
    for (std::size_t k = 0; k + 1 < frames.size(); ++k) {
        t.drifts.push_back(estimateDrift(frames[k], frames[k + 1], maxShift));
        step.push_back(links(frames[k], frames[k + 1], t.drifts.back()));
    }
    // Forward: which clouds descend from the first frame's.
    std::vector<std::uint8_t> reached(frames[0].regions.area.size(), 1);
    for (std::size_t k = 0; k + 1 < frames.size(); ++k) {
        std::vector<std::uint8_t> next(frames[k + 1].regions.area.size(), 0);
        for (std::size_t a = 0; a < reached.size(); ++a)
            if (reached[a])
                for (const std::int32_t b : step[k][a]) next[static_cast<std::size_t>(b)] = 1;
        reached = std::move(next);
    }
    // Backward: which clouds have a descendant in the last frame.
    std::vector<std::uint8_t> lives(frames.back().regions.area.size(), 1);
    for (std::size_t k = frames.size() - 1; k-- > 0;) {
        std::vector<std::uint8_t> before(frames[k].regions.area.size(), 0);
        for (std::size_t a = 0; a < before.size(); ++a)
            for (const std::int32_t b : step[k][a])
                before[a] = before[a] || lives[static_cast<std::size_t>(b)];
        lives = std::move(before);
    }
    const Regions& first = frames.front().regions;
    const Regions& last = frames.back().regions;
    t.firstClouds = countLarge(first, minCells);
    t.lastClouds = countLarge(last, minCells);
    for (std::size_t a = 0; a < first.area.size(); ++a)
        t.gone += first.area[a] >= minCells && !lives[a] ? 1 : 0;
    for (std::size_t b = 0; b < last.area.size(); ++b)
        t.born += last.area[b] >= minCells && !reached[b] ? 1 : 0;
    return t;
}

}  // namespace cg::algo
