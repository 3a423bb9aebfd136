#include "algo/mapping/Mapping.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_set>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "algo/CounterRandom.h"

namespace cg::algo {

float MapView::at(double x, double y) const
{
    const int ix = static_cast<int>(std::clamp(std::floor(x / cellSize), 0.0, nx - 1.0));
    const int iy = static_cast<int>(std::clamp(std::floor(y / cellSize), 0.0, ny - 1.0));
    return values[static_cast<std::size_t>(iy) * static_cast<std::size_t>(nx) +
                  static_cast<std::size_t>(ix)];
}

double selectionRatio(const MappingSettings& s, int level)
{
    const auto i = static_cast<std::size_t>(level - 1);
    return s.selectionRatio.empty() ? 0.0
                                    : s.selectionRatio[std::min(i, s.selectionRatio.size() - 1)];
}

int windowLength(const MappingSettings& s, int level)
{
    const auto i = static_cast<std::size_t>(level - 1);
    return s.windowLength.empty() ? 0 : s.windowLength[std::min(i, s.windowLength.size() - 1)];
}

PrimitiveLibrary::PrimitiveLibrary(std::vector<PrimitiveView> several) : views(std::move(several))
{
    if (views.empty() || views.size() > kMaxPrimitives)
        throw std::invalid_argument("a primitive library holds 1 to 8 primitives");
}

namespace {

/// The counter-based stream of the sources' primitives (levels use streams below 2^40).
constexpr std::uint64_t kPrimitiveStream = std::uint64_t{1} << 43;

/// Refuses a library that is not the one the settings' table was made with.
void checkLibrary(const PrimitiveLibrary& lib, const MappingSettings& s)
{
    if (lib.views.size() != s.primitiveCount)
        throw std::invalid_argument("the mapping was made with " +
                                    std::to_string(s.primitiveCount) + " primitives, not " +
                                    std::to_string(lib.views.size()));
}

/// The primitive source j plays.
const PrimitiveView& viewOf(const PrimitiveLibrary& lib, std::size_t j, const MappingSettings& s)
{
    return lib.views[primitiveOf(j, s)];
}

/// Each primitive's drift (primitiveDrift), by its index in the library.
using Drifts = std::vector<std::array<float, 3>>;
Drifts drifts(const PrimitiveLibrary& lib)
{
    Drifts out(lib.views.size());
    for (std::size_t i = 0; i < lib.views.size(); ++i) primitiveDrift(lib.views[i], out[i].data());
    return out;
}

}  // namespace

std::size_t primitiveOf(std::size_t j, const MappingSettings& s)
{
    if (s.primitiveCount <= 1) return 0;
    return static_cast<std::size_t>(counterBits(s.seed, kPrimitiveStream, j) % s.primitiveCount);
}

double primitiveTime(const Source& src, int frame, const MappingSettings& s, const PrimitiveView& p)
{
    return src.speed * static_cast<double>(frame - src.startFrame) * s.timeStep / p.frameTime;
}

std::uint32_t copyStride(const MappingSettings& s, const PrimitiveView& p)
{
    if (s.particlesPerCopy == 0 || p.frameCount == 0) return 1;
    const std::uint64_t last = p.counts[p.frameCount - 1];
    const std::uint64_t k = (last + s.particlesPerCopy - 1) / s.particlesPerCopy;
    return static_cast<std::uint32_t>(std::clamp<std::uint64_t>(k, 1, 65536));
}

std::uint32_t clusterSize(const Source& src, int frame, const MappingSettings& s,
                          const PrimitiveView& p)
{
    if (frame < src.startFrame || p.frameCount == 0) return 0;
    const double t = std::floor(primitiveTime(src, frame, s, p));
    const int index = t >= p.frameCount - 1 ? p.frameCount - 1 : static_cast<int>(t);
    const std::uint32_t n = p.counts[index];
    const std::uint32_t k = copyStride(s, p);
    return n > src.phase ? (n - src.phase + k - 1) / k : 0;
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

void primitiveDrift(const PrimitiveView& p, float out[3])
{
    out[0] = out[1] = out[2] = 0.0f;
    if (p.frameCount < 2) return;
    const int last = p.frameCount - 1;
    const int first = std::max(0, last - kDriftFrames);
    const std::uint32_t n = std::min(p.counts[first], p.counts[last]);
    if (n == 0) return;
    // In double and in id order: the same drift for any thread count.
    double sum[3] = {0.0, 0.0, 0.0};
    for (std::uint32_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k)
            sum[k] += static_cast<double>(p.frames[last][3 * i + k]) - p.frames[first][3 * i + k];
    for (int k = 0; k < 3; ++k) out[k] = static_cast<float>(sum[k] / n / (last - first));
}

void copyShift(const PrimitiveView& p, const MappingSettings& s, const float drift[3], double time,
               float out[3])
{
    const double past = time - (p.frameCount - 1);
    const bool drifting = s.pastLastFrame == PastLastFrame::Drift && past > 0.0;
    const double travelled =
        drifting ? kDriftDecayFrames * -std::expm1(-past / kDriftDecayFrames) : 0.0;
    for (int k = 0; k < 3; ++k) out[k] = static_cast<float>(travelled * drift[k]);
}

namespace {

/// Where source src's copy stands at primitive time `time`: its origin (Eq. 12) plus its drift
/// past the primitive's end; its particles are this plus R P_f (Eq. 10).
void copyOrigin(const Source& src, const float* sourceOrigin, double time, const PrimitiveView& p,
                const MappingSettings& s, const float drift[3], float out[3])
{
    const auto scale = static_cast<float>(s.metresPerPrimitiveMetre * src.scale);
    float shift[3];
    copyShift(p, s, drift, time, shift);
    for (int k = 0; k < 3; ++k) out[k] = sourceOrigin[k] + scale * shift[k];
}

/// Eq. 10 for one particle: fluid id i of the copy of `src` that stands at `copyAt` (its
/// copyOrigin), with the arithmetic of sourceSlice (copyAt + r P_f), so a child's origin is bit
/// for bit its parent particle.
void cloudParticlePosition(const Source& src, const float* copyAt, std::uint32_t i, int frame,
                           const PrimitiveView& p, const MappingSettings& s, float out[3])
{
    float f[3];
    primitivePosition(p, i, primitiveTime(src, frame, s, p), f);
    const auto r = static_cast<float>(s.metresPerPrimitiveMetre * src.scale);
    for (int k = 0; k < 3; ++k) out[k] = copyAt[k] + r * f[k];
}

/// Per source, 3 floats each: its origin P_s[L, j](t) (Eq. 12) and where its copy stands
/// (copyOrigin: the origin plus its drift); zero for sources that start after t.
struct Origins {
    std::vector<float> origin;
    std::vector<float> copy;
};

/// Origins in one pass in table order (parents precede children): a child's origin is its
/// parent's particle, read off the parent's copy origin computed just before.
Origins originsWithDrift(const SourceTable& table, int frame, const CondensationView& c,
                         const PrimitiveLibrary& lib, const MappingSettings& s, const Drifts& drift)
{
    Origins out{std::vector<float>(3 * table.sources.size()),
                std::vector<float>(3 * table.sources.size())};
    for (std::size_t j = 0; j < table.sources.size(); ++j) {
        const Source& src = table.sources[j];
        float* o = &out.origin[3 * j];
        if (frame < src.startFrame) continue;  // not started yet: no cluster, no origin
        if (src.level == 1 && s.level1Origin == Level1Origin::Trail &&
            !std::isnan(table.anchors[3 * j])) {
            std::copy_n(&table.anchors[3 * j], 3, o);  // laid: it stays where it was laid
        } else if (src.level == 1) {  // Eq. 12, L = 1: the condensation particle itself
            o[0] = c.x[src.parent], o[1] = c.y[src.parent];
            o[2] = s.level1Origin == Level1Origin::CondensationLevel ? c.condensedZ[src.parent]
                                                                     : c.z[src.parent];
        } else {  // Eq. 12, L >= 2: the parent cloud particle, placed by Eq. 10 (as sourceSlice
                  // does)
            cloudParticlePosition(table.sources[src.parent],
                                  &out.copy[3 * static_cast<std::size_t>(src.parent)],
                                  src.parentFluid, frame, viewOf(lib, src.parent, s), s, o);
        }
        const std::size_t primitive = primitiveOf(j, s);
        const PrimitiveView& p = lib.views[primitive];
        copyOrigin(src, o, primitiveTime(src, frame, s, p), p, s, drift[primitive].data(),
                   &out.copy[3 * j]);
    }
    return out;
}

}  // namespace

std::vector<float> sourceOrigins(const SourceTable& table, int frame, const CondensationView& c,
                                 const PrimitiveLibrary& lib, const MappingSettings& s)
{
    checkLibrary(lib, s);
    return originsWithDrift(table, frame, c, lib, s, drifts(lib)).origin;
}

std::vector<std::uint64_t> cloudCounts(const SourceTable& table, int frame,
                                       const PrimitiveLibrary& lib, const MappingSettings& s)
{
    checkLibrary(lib, s);
    std::vector<std::uint64_t> counts(static_cast<std::size_t>(std::max(s.maxLevel, 1)), 0);
    for (std::size_t j = 0; j < table.sources.size(); ++j) {
        const Source& src = table.sources[j];
        if (src.level >= 1 && src.level <= counts.size())
            counts[src.level - 1u] += clusterSize(src, frame, s, viewOf(lib, j, s));
    }
    return counts;
}

namespace {

/// The counter-based stream of the copies' phases (levels use streams below 2^40).
constexpr std::uint64_t kPhaseStream = std::uint64_t{1} << 40;
/// The streams of Eq. 15's draws of a parent source and of a particle in it, one per
/// (level, frame) below each.
constexpr std::uint64_t kParentStream = std::uint64_t{1} << 41;
constexpr std::uint64_t kParticleStream = std::uint64_t{1} << 42;

/// Picks the k-th new candidate of (level, frame) uniformly in [0, n), skipping taken ones by
/// probing forward: a candidate becomes a source at most once.
template <class Taken>
std::uint64_t pickCandidate(const MappingSettings& s, int level, int frame, std::uint64_t k,
                            std::uint64_t n, const Taken& taken)
{
    const std::uint64_t stream =
        (static_cast<std::uint64_t>(level) << 32) | static_cast<std::uint32_t>(frame);
    std::uint64_t u = counterBits(s.seed, stream, k) % n;
    while (taken(u)) u = u + 1 == n ? 0 : u + 1;
    return u;
}

/// The level L-1 cloud particles a level L >= 2 source may start from at one frame: source
/// parents[n] holds candidates [parentOffset[n], parentOffset[n + 1]) (or up to `count`).
struct ParentCandidates {
    int level = 2;
    int frame = 0;
    const std::vector<std::uint32_t>& parents;
    const std::vector<std::uint64_t>& parentOffset;
    std::uint64_t count = 0;
};

/// The keys (j' << 32 | q) of up to `fresh` new parent cloud particles, none taken before
/// (Eq. 15, by the settings' rule), in the order the sources are made.
std::vector<std::uint64_t> pickParents(const SourceTable& table, const ParentCandidates& c,
                                       std::uint64_t fresh, const MappingSettings& s)
{
    std::vector<std::uint64_t> keys;
    std::unordered_set<std::uint64_t> takenNow;
    auto taken = [&](std::uint64_t key) {
        return takenNow.count(key) != 0 ||
               std::binary_search(table.cloudTaken.begin(), table.cloudTaken.end(), key);
    };
    auto take = [&](std::uint64_t key) {
        takenNow.insert(key);
        keys.push_back(key);
    };
    if (s.parentRule == ParentRule::PerParticle) {
        auto keyOf = [&](std::uint64_t v) {
            const auto at = std::upper_bound(c.parentOffset.begin(), c.parentOffset.end(), v) - 1;
            const auto slot = static_cast<std::size_t>(at - c.parentOffset.begin());
            return (static_cast<std::uint64_t>(c.parents[slot]) << 32) | (v - *at);
        };
        for (std::uint64_t k = 0; k < fresh; ++k)
            take(keyOf(pickCandidate(s, c.level, c.frame, k, c.count,
                                     [&](std::uint64_t v) { return taken(keyOf(v)); })));
        return keys;
    }
    // The paper's rule: r_j uniformly among the sources that have particles, then r_i
    // uniformly among r_j's particles that are still free. A parent whose particles are all
    // taken is drawn again, so r_j stays uniform over the parents that can give one.
    std::vector<std::uint32_t> eligible;
    std::vector<std::uint64_t> sizes, takenIn;
    for (std::size_t n = 0; n < c.parents.size(); ++n) {
        const std::uint64_t end = n + 1 < c.parents.size() ? c.parentOffset[n + 1] : c.count;
        if (end == c.parentOffset[n]) continue;
        const std::uint64_t j = c.parents[n], size = end - c.parentOffset[n];
        eligible.push_back(c.parents[n]);
        sizes.push_back(size);
        // Taken particles of j below its size now (a cluster that shrank keeps older keys).
        takenIn.push_back(static_cast<std::uint64_t>(
            std::lower_bound(table.cloudTaken.begin(), table.cloudTaken.end(), (j << 32) | size) -
            std::lower_bound(table.cloudTaken.begin(), table.cloudTaken.end(), j << 32)));
    }
    std::uint64_t freeLeft = 0;
    for (std::size_t n = 0; n < eligible.size(); ++n) freeLeft += sizes[n] - takenIn[n];
    const std::uint64_t key =
        (static_cast<std::uint64_t>(c.level) << 32) | static_cast<std::uint32_t>(c.frame);
    std::uint64_t parentDraw = 0, particleDraw = 0;
    while (keys.size() < fresh && freeLeft > 0) {
        const std::size_t n =
            counterBits(s.seed, kParentStream | key, parentDraw++) % eligible.size();
        if (takenIn[n] >= sizes[n]) continue;
        std::uint64_t pair;
        do {
            const std::uint64_t q =
                counterBits(s.seed, kParticleStream | key, particleDraw++) % sizes[n];
            pair = (static_cast<std::uint64_t>(eligible[n]) << 32) | q;
        } while (taken(pair));
        take(pair);
        ++takenIn[n];
        --freeLeft;
    }
    return keys;
}

}  // namespace

SourceTable stepSources(const SourceTable& previous, int frame, int firstCondensation,
                        const CondensationView& c, const MapView& map, const PrimitiveLibrary& lib,
                        const MappingSettings& s)
{
    checkLibrary(lib, s);
    if (s.level1Origin == Level1Origin::Trail && c.vz == nullptr)
        throw std::invalid_argument(
            "stepSources: level1Origin trail needs the particles' vertical speeds");
    SourceTable table = previous;
    const Drifts drift = drifts(lib);
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
                candidates += clusterSize(table.sources[j], frame, s, viewOf(lib, j, s));
            }
        }
        std::uint64_t existing = 0;
        for (const Source& src : table.sources) existing += src.level == level;
        // Eq. 14: G[L](t) = M[L] x candidates, rounded down.
        const auto target = static_cast<std::uint64_t>(
            std::floor(selectionRatio(s, level) * static_cast<double>(candidates)));
        std::uint64_t fresh = target > existing ? target - existing : 0;
        fresh = std::min<std::uint64_t>(
            fresh, s.maxSources > table.sources.size() ? s.maxSources - table.sources.size() : 0);
        if (fresh == 0) continue;

        const std::vector<float> copies =
            level == 1 ? std::vector<float>()
                       : originsWithDrift(table, frame, c, lib, s, drift).copy;
        const std::vector<std::uint64_t> parentKeys =
            level == 1
                ? std::vector<std::uint64_t>()
                : pickParents(table,
                              ParentCandidates{level, frame, parents, parentOffset, candidates},
                              fresh, s);
        for (std::uint64_t k = 0; k < fresh; ++k) {
            Source src;
            src.level = static_cast<std::uint8_t>(level);
            src.startFrame = frame;
            double x, y;
            if (level == 1) {
                const std::uint64_t u = pickCandidate(
                    s, level, frame, k, candidates,
                    [&](std::uint64_t v) { return table.condensationTaken[condensed[v]] != 0; });
                src.parent = condensed[u];
                table.condensationTaken[src.parent] = 1;
                x = c.x[src.parent];
                y = c.y[src.parent];
            } else {
                if (k >= parentKeys.size()) break;  // every draw hit a taken particle
                const std::uint64_t key = parentKeys[k];
                src.parent = static_cast<std::uint32_t>(key >> 32);
                const PrimitiveView& parentView = viewOf(lib, src.parent, s);
                src.parentFluid = copyFluidId(table.sources[src.parent], key & 0xffffffffu,
                                              copyStride(s, parentView));
                // Eq. 16 reads the map under the parent cloud particle's position (Eq. 10).
                float at[3];
                cloudParticlePosition(table.sources[src.parent], &copies[3 * src.parent],
                                      src.parentFluid, frame, parentView, s, at);
                x = at[0];
                y = at[1];
            }
            // Which of the primitive's particles this copy carries, keyed by the source's index,
            // so it never depends on thread order.
            src.phase =
                static_cast<std::uint16_t>(counterBits(s.seed, kPhaseStream, table.sources.size()) %
                                           copyStride(s, viewOf(lib, table.sources.size(), s)));
            const double noise = map.at(x, y);  // Eq. 16
            src.scale = static_cast<float>(s.scaleCoefficient * noise);
            src.speed = static_cast<float>(1.0 + s.speedCoefficient * noise);
            if (s.level1Origin == Level1Origin::Trail) {
                // Deeper copies stand on their parents (zero); a level 1 copy is laid where a
                // rising particle is, or rides one that has stopped rising (NaN).
                const bool rises = level == 1 && c.vz[src.parent] >= s.trailRiseSpeed;
                const float none = level == 1 ? std::numeric_limits<float>::quiet_NaN() : 0.0f;
                table.anchors.push_back(rises ? c.x[src.parent] : none);
                table.anchors.push_back(rises ? c.y[src.parent] : none);
                table.anchors.push_back(rises ? c.z[src.parent] : none);
            }
            table.sources.push_back(src);
        }
        if (!parentKeys.empty()) {
            table.cloudTaken.insert(table.cloudTaken.end(), parentKeys.begin(), parentKeys.end());
            std::sort(table.cloudTaken.begin(), table.cloudTaken.end());
        }
    }
    // Pseudocode lines 26-27: once the top level has cloud particles, the next may start.
    if (table.topLevel < s.maxLevel &&
        cloudCounts(table, frame, lib, s)[static_cast<std::size_t>(table.topLevel - 1)] > 0)
        ++table.topLevel;
    return table;
}

namespace {

/// What every chunk of frame t needs: where each source's copy stands (copyOrigin: Eq. 12's
/// origin plus its drift; zero before the source starts) and the prefix sums of the cluster
/// sizes (Eq. 13), so particle q belongs to the source j with offset[j] <= q < offset[j + 1].
struct FramePlan {
    std::vector<float> copyOrigins;
    std::vector<std::uint64_t> offset;
    std::uint64_t total() const { return offset.back(); }
};

FramePlan planFrame(const SourceTable& table, int frame, const CondensationView& c,
                    const PrimitiveLibrary& lib, const MappingSettings& s)
{
    checkLibrary(lib, s);
    FramePlan plan;
    plan.copyOrigins = originsWithDrift(table, frame, c, lib, s, drifts(lib)).copy;
    const std::size_t n = table.sources.size();
    plan.offset.assign(n + 1, 0);
    for (std::size_t j = 0; j < n; ++j)
        plan.offset[j + 1] =
            plan.offset[j] + clusterSize(table.sources[j], frame, s, viewOf(lib, j, s));
    return plan;
}

/// Eq. 10 for particles [i0, i1) of one copy, whose fluid ids are first, first + k, ...:
/// primitivePosition's arithmetic (P_f = a + w (b - a), or the last frame past its end) with
/// the frame pair, weight, origin and scale hoisted out of the particle loop, bit-identical to
/// calling it per particle. K is the stride when known at compile time (1: contiguous ids, the
/// loop the compiler vectorises), 0 when it is `stride`.
template <std::uint32_t K>
void copySlice(const float* __restrict a, const float* __restrict b, float w, bool lerp,
               std::size_t stride, const float* origin, float scale, std::uint64_t n,
               float* __restrict out)
{
    const std::size_t step = 3 * (K != 0 ? K : stride);
    const float ox = origin[0], oy = origin[1], oz = origin[2];
    if (!lerp) {
        for (std::uint64_t i = 0; i < n; ++i) {
            const float* q = a + i * step;
            out[3 * i] = ox + scale * q[0];
            out[3 * i + 1] = oy + scale * q[1];
            out[3 * i + 2] = oz + scale * q[2];
        }
        return;
    }
    for (std::uint64_t i = 0; i < n; ++i) {
        const float* qa = a + i * step;
        const float* qb = b + i * step;
        out[3 * i] = ox + scale * (qa[0] + w * (qb[0] - qa[0]));
        out[3 * i + 1] = oy + scale * (qa[1] + w * (qb[1] - qa[1]));
        out[3 * i + 2] = oz + scale * (qa[2] + w * (qb[2] - qa[2]));
    }
}

/// Eq. 10 for particles [i0, i1) of the copy of `src` that stands at `origin` (copyOrigin).
void sourceSlice(const Source& src, const float* origin, int frame, const PrimitiveView& p,
                 const MappingSettings& s, std::uint32_t stride, std::uint64_t i0, std::uint64_t i1,
                 float* __restrict out)
{
    const double time = primitiveTime(src, frame, s, p);
    const auto scale = static_cast<float>(s.metresPerPrimitiveMetre * src.scale);
    const double whole = std::floor(time);
    const bool past = whole >= p.frameCount - 1;
    const int f = past ? p.frameCount - 1 : static_cast<int>(whole);
    const auto w = past ? 0.0f : static_cast<float>(time - whole);
    const std::size_t first = 3 * static_cast<std::size_t>(copyFluidId(src, i0, stride));
    const float* a = p.frames[f] + first;
    const float* b = past ? a : p.frames[f + 1] + first;
    if (stride == 1)
        copySlice<1>(a, b, w, !past, 1, origin, scale, i1 - i0, out);
    else
        copySlice<0>(a, b, w, !past, stride, origin, scale, i1 - i0, out);
}

/// Particles [first, last) of the frame into xyz (and levels / sources when not null), source
/// slice by source slice.
void fillRange(const FramePlan& plan, const SourceTable& table, int frame,
               const PrimitiveLibrary& lib, const MappingSettings& s, std::uint64_t first,
               std::uint64_t last, float* xyz, std::uint8_t* levels, std::uint32_t* sources)
{
    const auto& offset = plan.offset;
    auto j = static_cast<std::size_t>(std::upper_bound(offset.begin(), offset.end(), first) -
                                      offset.begin() - 1);
    for (std::uint64_t q = first; q < last; ++j) {
        const std::uint64_t end = std::min(last, offset[j + 1]);
        if (end == q) continue;  // a source not started yet: no cluster, no frame to look up
        const Source& src = table.sources[j];
        const PrimitiveView& p = viewOf(lib, j, s);
        sourceSlice(src, &plan.copyOrigins[3 * j], frame, p, s, copyStride(s, p), q - offset[j],
                    end - offset[j], xyz + 3 * (q - first));
        if (levels != nullptr) std::fill_n(levels + (q - first), end - q, src.level);
        if (sources != nullptr)
            std::fill_n(sources + (q - first), end - q, static_cast<std::uint32_t>(j));
        q = end;
    }
}

/// The chunk loop behind forEachCloudChunk and generateCloudParticles.
void runChunks(const FramePlan& plan, const SourceTable& table, int frame,
               const PrimitiveLibrary& lib, const MappingSettings& s,
               const std::function<void(const CloudChunk&)>& consume, const CloudChunkOptions& o)
{
    const std::uint64_t size = o.chunkParticles;
    const bool direct = o.positionsOut != nullptr;
    if (size == 0)
        throw std::invalid_argument("forEachCloudChunk: chunkParticles must be positive");
    if (direct ? (o.levels && o.levelsOut == nullptr) || (o.sources && o.sourcesOut == nullptr)
               : o.levelsOut != nullptr || o.sourcesOut != nullptr)
        throw std::invalid_argument(
            "forEachCloudChunk: frame arrays must be given for every requested field");
    const std::uint64_t total = plan.total();
    const std::uint64_t chunks = total / size + (total % size != 0);
    struct Buffers {
        std::vector<float> xyz;
        std::vector<std::uint8_t> levels;
        std::vector<std::uint32_t> sources;
    };
    tbb::enumerable_thread_specific<Buffers> perThread;
    // Chunk k is particles [k size, (k + 1) size): fixed by the inputs, whatever the partition.
    tbb::parallel_for(tbb::blocked_range<std::uint64_t>(0, chunks),
                      [&](const tbb::blocked_range<std::uint64_t>& r) {
                          for (std::uint64_t k = r.begin(); k < r.end(); ++k) {
                              if (o.checkCancelled) o.checkCancelled();
                              CloudChunk chunk;
                              chunk.first = k * size;
                              chunk.count = std::min(size, total - chunk.first);
                              float* xyz;
                              std::uint8_t* levels = nullptr;
                              std::uint32_t* sources = nullptr;
                              if (direct) {
                                  xyz = o.positionsOut + 3 * chunk.first;
                                  if (o.levels) levels = o.levelsOut + chunk.first;
                                  if (o.sources) sources = o.sourcesOut + chunk.first;
                              } else {
                                  Buffers& b = perThread.local();
                                  if (b.xyz.empty()) {
                                      b.xyz.resize(3 * size);
                                      if (o.levels) b.levels.resize(size);
                                      if (o.sources) b.sources.resize(size);
                                  }
                                  xyz = b.xyz.data();
                                  if (o.levels) levels = b.levels.data();
                                  if (o.sources) sources = b.sources.data();
                              }
                              fillRange(plan, table, frame, lib, s, chunk.first,
                                        chunk.first + chunk.count, xyz, levels, sources);
                              if (consume) {
                                  chunk.positions = xyz;
                                  chunk.levels = levels;
                                  chunk.sources = sources;
                                  chunk.copyOrigins = plan.copyOrigins.data();
                                  chunk.copyCount = plan.copyOrigins.size() / 3;
                                  consume(chunk);
                              }
                          }
                      });
}

}  // namespace

std::uint64_t forEachCloudChunk(const SourceTable& table, int frame, const CondensationView& c,
                                const PrimitiveLibrary& lib, const MappingSettings& s,
                                const std::function<void(const CloudChunk&)>& consume,
                                const CloudChunkOptions& options)
{
    const FramePlan plan = planFrame(table, frame, c, lib, s);
    runChunks(plan, table, frame, lib, s, consume, options);
    return plan.total();
}

CloudParticleArrays generateCloudParticles(const SourceTable& table, int frame,
                                           const CondensationView& c, const PrimitiveLibrary& lib,
                                           const MappingSettings& s,
                                           const std::function<void()>& checkCancelled)
{
    const FramePlan plan = planFrame(table, frame, c, lib, s);
    const auto n = static_cast<std::size_t>(plan.total());
    // Uninitialised: each chunk's writer touches its own pages first (no zero-fill on one thread).
    CloudParticleArrays out{UninitArray<float>(3 * n), UninitArray<std::uint8_t>(n),
                            UninitArray<std::uint32_t>(n), UninitArray<float>(plan.copyOrigins)};
    CloudChunkOptions o;
    o.levels = o.sources = true;
    o.positionsOut = out.positions.data();
    o.levelsOut = out.levels.data();
    o.sourcesOut = out.sources.data();
    o.checkCancelled = checkCancelled;
    runChunks(plan, table, frame, lib, s, {}, o);
    return out;
}

}  // namespace cg::algo
