#include "nodes/algo/Mapping.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "nodes/algo/CounterRandom.h"

namespace cg::algo {

float MapView::at(double x, double y) const
{
    const int ix = static_cast<int>(std::clamp(std::floor(x / cellSize), 0.0, nx - 1.0));
    const int iy = static_cast<int>(std::clamp(std::floor(y / cellSize), 0.0, ny - 1.0));
    return values[static_cast<std::size_t>(iy) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(ix)];
}

double selectionRatio(const MappingSettings& s, int level)
{
    const auto i = static_cast<std::size_t>(level - 1);
    return s.selectionRatio.empty() ? 0.0 : s.selectionRatio[std::min(i, s.selectionRatio.size() - 1)];
}

int windowLength(const MappingSettings& s, int level)
{
    const auto i = static_cast<std::size_t>(level - 1);
    return s.windowLength.empty() ? 0 : s.windowLength[std::min(i, s.windowLength.size() - 1)];
}

double primitiveTime(const Source& src, int frame, const MappingSettings& s, const PrimitiveView& p)
{
    return src.speed * static_cast<double>(frame - src.startFrame) * s.timeStep / p.frameTime;
}

std::uint32_t clusterSize(const Source& src, int frame, const MappingSettings& s, const PrimitiveView& p)
{
    if (frame < src.startFrame || p.frameCount == 0) return 0;
    const double t = std::floor(primitiveTime(src, frame, s, p));
    const int index = t >= p.frameCount - 1 ? p.frameCount - 1 : static_cast<int>(t);
    return p.counts[index];
}

void primitivePosition(const PrimitiveView& p, std::uint32_t i, double s, float out[3])
{
    const double whole = std::floor(s);
    if (whole >= p.frameCount - 1) {
        const float* q = p.frames[p.frameCount - 1] + 3 * static_cast<std::size_t>(i);
        out[0] = q[0], out[1] = q[1], out[2] = q[2];
        return;
    }
    const int f = static_cast<int>(whole);
    const auto w = static_cast<float>(s - whole);
    const float* a = p.frames[f] + 3 * static_cast<std::size_t>(i);
    const float* b = p.frames[f + 1] + 3 * static_cast<std::size_t>(i);
    for (int k = 0; k < 3; ++k) out[k] = a[k] + w * (b[k] - a[k]);
}

std::vector<float> sourceOrigins(const SourceTable& table, int frame, const CondensationView& c,
                                 const PrimitiveView& p, const MappingSettings& s)
{
    // Parents precede children in the table, so one pass in order suffices.
    std::vector<float> origins(3 * table.sources.size());
    for (std::size_t j = 0; j < table.sources.size(); ++j) {
        const Source& src = table.sources[j];
        float* o = &origins[3 * j];
        if (frame < src.startFrame) continue;  // not started yet: no cluster, no origin
        if (src.level == 1) {  // Eq. 12, L = 1: the condensation particle itself
            o[0] = c.x[src.parent], o[1] = c.y[src.parent], o[2] = c.z[src.parent];
            continue;
        }
        // Eq. 12, L >= 2: the parent cloud particle, placed by Eq. 10.
        const Source& parent = table.sources[src.parent];
        const float* po = &origins[3 * static_cast<std::size_t>(src.parent)];
        float f[3];
        primitivePosition(p, src.parentFluid, primitiveTime(parent, frame, s, p), f);
        const auto r = static_cast<float>(s.metresPerPrimitiveMetre * parent.scale);
        for (int k = 0; k < 3; ++k) o[k] = po[k] + r * f[k];
    }
    return origins;
}

std::vector<std::uint64_t> cloudCounts(const SourceTable& table, int frame, const PrimitiveView& p,
                                       const MappingSettings& s)
{
    std::vector<std::uint64_t> counts(static_cast<std::size_t>(std::max(s.maxLevel, 1)), 0);
    for (const Source& src : table.sources)
        if (src.level >= 1 && src.level <= counts.size()) counts[src.level - 1u] += clusterSize(src, frame, s, p);
    return counts;
}

namespace {

/// Picks the k-th new candidate of (level, frame) uniformly in [0, n), skipping taken ones by
/// probing forward: a candidate becomes a source at most once.
template <class Taken>
std::uint64_t pickCandidate(const MappingSettings& s, int level, int frame, std::uint64_t k,
                            std::uint64_t n, const Taken& taken)
{
    const std::uint64_t stream = (static_cast<std::uint64_t>(level) << 32) | static_cast<std::uint32_t>(frame);
    std::uint64_t u = counterBits(s.seed, stream, k) % n;
    while (taken(u)) u = u + 1 == n ? 0 : u + 1;
    return u;
}

}  // namespace

SourceTable stepSources(const SourceTable& previous, int frame, int firstCondensation,
                        const CondensationView& c, const MapView& map, const PrimitiveView& p,
                        const MappingSettings& s)
{
    SourceTable table = previous;
    table.condensationTaken.resize(c.count, 0);
    table.levelStart.assign(static_cast<std::size_t>(s.maxLevel), -1);
    const int first = s.firstStart >= 0 ? s.firstStart : firstCondensation;
    for (int level = 1; level <= s.maxLevel && first >= 0; ++level)
        table.levelStart[static_cast<std::size_t>(level - 1)] = first + (level - 1) * s.levelDelay;

    for (int level = 1; level <= std::min(table.topLevel, s.maxLevel); ++level) {
        const int start = table.levelStart[static_cast<std::size_t>(level - 1)];
        if (start < 0 || frame < start || frame > start + windowLength(s, level)) continue;

        // The candidates: condensation particles (L = 1) or level L-1 cloud particles.
        std::vector<std::uint32_t> condensed;
        std::vector<std::uint32_t> parents;       // level L-1 source indices
        std::vector<std::uint64_t> parentOffset;  // first candidate of each parent
        std::uint64_t candidates = 0;
        if (level == 1) {
            for (std::size_t k = 0; k < c.count; ++k)
                if (c.condensedFrame[k] >= 0 && c.condensedFrame[k] <= frame)
                    condensed.push_back(static_cast<std::uint32_t>(k));
            candidates = condensed.size();
        } else {
            for (std::size_t j = 0; j < table.sources.size(); ++j) {
                if (table.sources[j].level != level - 1) continue;
                parents.push_back(static_cast<std::uint32_t>(j));
                parentOffset.push_back(candidates);
                candidates += clusterSize(table.sources[j], frame, s, p);
            }
        }
        std::uint64_t existing = 0;
        for (const Source& src : table.sources) existing += src.level == level;
        // Eq. 14: G[L](t) = M[L] x candidates, rounded down.
        const auto target = static_cast<std::uint64_t>(std::floor(selectionRatio(s, level) * static_cast<double>(candidates)));
        std::uint64_t fresh = target > existing ? target - existing : 0;
        fresh = std::min<std::uint64_t>(fresh, s.maxSources > table.sources.size() ? s.maxSources - table.sources.size() : 0);
        if (fresh == 0) continue;

        const std::vector<float> origins =
            level == 1 ? std::vector<float>() : sourceOrigins(table, frame, c, p, s);
        std::unordered_set<std::uint64_t> takenNow;
        for (std::uint64_t k = 0; k < fresh; ++k) {
            Source src;
            src.level = static_cast<std::uint8_t>(level);
            src.startFrame = frame;
            double x, y;
            if (level == 1) {
                const std::uint64_t u = pickCandidate(s, level, frame, k, candidates, [&](std::uint64_t v) {
                    return table.condensationTaken[condensed[v]] != 0;
                });
                src.parent = condensed[u];
                table.condensationTaken[src.parent] = 1;
                x = c.x[src.parent];
                y = c.y[src.parent];
            } else {
                auto keyOf = [&](std::uint64_t v) {
                    const auto at = std::upper_bound(parentOffset.begin(), parentOffset.end(), v) - 1;
                    const auto slot = static_cast<std::size_t>(at - parentOffset.begin());
                    return (static_cast<std::uint64_t>(parents[slot]) << 32) | (v - *at);
                };
                const std::uint64_t u = pickCandidate(s, level, frame, k, candidates, [&](std::uint64_t v) {
                    const std::uint64_t key = keyOf(v);
                    return takenNow.count(key) ||
                           std::binary_search(table.cloudTaken.begin(), table.cloudTaken.end(), key);
                });
                const std::uint64_t key = keyOf(u);
                takenNow.insert(key);
                src.parent = static_cast<std::uint32_t>(key >> 32);
                src.parentFluid = static_cast<std::uint32_t>(key & 0xffffffffu);
                // Eq. 16 reads the map under the parent cloud particle's position (Eq. 10).
                const Source& parent = table.sources[src.parent];
                float f[3];
                primitivePosition(p, src.parentFluid, primitiveTime(parent, frame, s, p), f);
                const double r = s.metresPerPrimitiveMetre * parent.scale;
                x = origins[3 * src.parent] + r * f[0];
                y = origins[3 * src.parent + 1] + r * f[1];
            }
            const double noise = map.at(x, y);  // Eq. 16
            src.scale = static_cast<float>(s.scaleCoefficient * noise);
            src.speed = static_cast<float>(1.0 + s.speedCoefficient * noise);
            table.sources.push_back(src);
        }
        if (!takenNow.empty()) {
            table.cloudTaken.insert(table.cloudTaken.end(), takenNow.begin(), takenNow.end());
            std::sort(table.cloudTaken.begin(), table.cloudTaken.end());
        }
    }
    // Pseudocode lines 26-27: once the top level has cloud particles, the next may start.
    if (table.topLevel < s.maxLevel && cloudCounts(table, frame, p, s)[static_cast<std::size_t>(table.topLevel - 1)] > 0)
        ++table.topLevel;
    return table;
}

CloudParticleArrays generateCloudParticles(const SourceTable& table, int frame,
                                           const CondensationView& c, const PrimitiveView& p,
                                           const MappingSettings& s,
                                           const std::function<void()>& checkCancelled)
{
    const std::vector<float> origins = sourceOrigins(table, frame, c, p, s);
    const std::size_t n = table.sources.size();
    std::vector<std::uint64_t> offset(n + 1, 0);
    for (std::size_t j = 0; j < n; ++j) offset[j + 1] = offset[j] + clusterSize(table.sources[j], frame, s, p);

    CloudParticleArrays out;
    out.positions.resize(3 * offset[n]);
    out.levels.resize(offset[n]);
    out.sources.resize(offset[n]);
    // Each source writes its own slice: the result does not depend on the thread count.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 64), [&](const tbb::blocked_range<std::size_t>& r) {
        if (checkCancelled) checkCancelled();
        for (std::size_t j = r.begin(); j < r.end(); ++j) {
            const Source& src = table.sources[j];
            const double time = primitiveTime(src, frame, s, p);
            const auto scale = static_cast<float>(s.metresPerPrimitiveMetre * src.scale);
            const float* o = &origins[3 * j];
            for (std::uint64_t q = offset[j]; q < offset[j + 1]; ++q) {
                float f[3];
                primitivePosition(p, static_cast<std::uint32_t>(q - offset[j]), time, f);
                for (int k = 0; k < 3; ++k) out.positions[3 * q + k] = o[k] + scale * f[k];  // Eq. 10
                out.levels[q] = src.level;
                out.sources[q] = static_cast<std::uint32_t>(j);
            }
        }
    });
    return out;
}

}  // namespace cg::algo
