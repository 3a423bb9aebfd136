// The mapper's source selection (Sec. 5.2, pseudocode lines 15-28, Eq. 14-16): which
// condensation or cloud particles become new sources at a frame, drawn from counter-based
// streams so that the table does not depend on thread order. Declared in Mapping.h.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unordered_set>

#include "algo/CounterRandom.h"
#include "algo/mapping/Mapping.h"
#include "algo/mapping/MappingInternal.h"

namespace cg::algo {

using mapping::checkLibrary;
using mapping::cloudParticlePosition;
using mapping::Drifts;
using mapping::drifts;
using mapping::kParentStream;
using mapping::kParticleStream;
using mapping::kPhaseStream;
using mapping::originsWithDrift;
using mapping::viewOf;

namespace {

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
    // The parents that have particles, and how many of each are taken: a particle drawn
    // for a copy the cloud top refused stays taken without a record, so the free ones, not
    // the fresh count, bound the draws.
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
    if (s.parentRule == ParentRule::PerParticle) {
        auto keyOf = [&](std::uint64_t v) {
            const auto at = std::upper_bound(c.parentOffset.begin(), c.parentOffset.end(), v) - 1;
            const auto slot = static_cast<std::size_t>(at - c.parentOffset.begin());
            return (static_cast<std::uint64_t>(c.parents[slot]) << 32) | (v - *at);
        };
        for (std::uint64_t k = 0; k < std::min(fresh, freeLeft); ++k)
            take(keyOf(pickCandidate(s, c.level, c.frame, k, c.count,
                                     [&](std::uint64_t v) { return taken(keyOf(v)); })));
        return keys;
    }
    // The paper's rule: r_j uniformly among the sources that have particles, then r_i
    // uniformly among r_j's particles that are still free. A parent whose particles are all
    // taken is drawn again, so r_j stays uniform over the parents that can give one.
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

/// How far a copy's fluid particle `i` ends up above the copy's origin at scale 1, primitive
/// metres: its height in the last frame plus the rise of the drift past it (Drift).
double finalFluidHeight(const PrimitiveView& p, std::uint32_t i, const MappingSettings& s,
                        const std::array<float, 3>& drift)
{
    const double rise = s.pastLastFrame == PastLastFrame::Drift
                            ? kDriftDecayFrames * std::max(0.0f, drift[2])
                            : 0.0;
    return p.frames[p.frameCount - 1][3 * static_cast<std::size_t>(i) + 2] + rise;
}

/// The highest any particle of a copy of `p` ends up above its origin at scale 1.
double primitiveTop(const PrimitiveView& p, const MappingSettings& s,
                    const std::array<float, 3>& drift)
{
    double top = 0.0;
    for (std::uint32_t i = 0; p.frameCount > 0 && i < p.counts[p.frameCount - 1]; ++i)
        top = std::max(top, finalFluidHeight(p, i, s, drift));
    return top;
}

/// Where source j's origin ends up (m): a level 1 copy's stays at its condensation height (or
/// where its particle is now, with the other origins); a deeper one's rises with its parent
/// particle until the parent's copy has played out.
double finalOriginHeight(const SourceTable& table, std::size_t j, const CondensationView& c,
                         const PrimitiveLibrary& lib, const MappingSettings& s, const Drifts& drift)
{
    const Source& src = table.sources[j];
    if (src.level == 1)
        return s.level1Origin == Level1Origin::CondensationLevel ? c.condensedZ[src.parent]
                                                                 : c.z[src.parent];
    const Source& parent = table.sources[src.parent];
    const std::size_t primitive = primitiveOf(src.parent, s);
    return finalOriginHeight(table, src.parent, c, lib, s, drift) +
           copyScale(parent, s).up *
               finalFluidHeight(lib.views[primitive], src.parentFluid, s, drift[primitive]);
}

/// Ours (MappingSettings::cloudTop): how much of its height a copy whose origin ends up at z
/// may keep so that its top stays under the cap (1: all, it fits); 0 when it would keep less
/// than kSmallestCappedScale.
double capShare(float scale, double z, double top, const MappingSettings& s)
{
    if (s.cloudTop <= 0.0 || top <= 0.0 || scale <= 0.0f) return 1.0;
    const double share = (s.cloudTop - z) / (top * s.metresPerPrimitiveMetre * scale);
    return share < kSmallestCappedScale ? 0.0 : std::min(1.0, share);
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
    std::vector<double> tops;
    for (std::size_t i = 0; i < lib.views.size(); ++i)
        tops.push_back(primitiveTop(lib.views[i], s, drift[i]));
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
        if (level == 1) {
            // A condensation particle drawn for a copy the cloud top refused stays taken
            // without a record: never draw more than are free.
            std::uint64_t free = 0;
            for (std::uint32_t v : condensed) free += table.condensationTaken[v] == 0;
            fresh = std::min(fresh, free);
        }
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
            if (s.cloudTop > 0.0) {  // the copy's top stays under cloudTop; too small: none
                table.sources.push_back(src);  // finalOriginHeight reads it as source j
                const std::size_t j = table.sources.size() - 1;
                const double z = finalOriginHeight(table, j, c, lib, s, drift);
                table.sources.pop_back();
                const double share = capShare(src.scale, z, tops[primitiveOf(j, s)], s);
                if (share == 0.0) continue;
                if (s.cloudTopRule == CloudTopRule::Spread)
                    src.flatten = static_cast<float>(share);
                else
                    src.scale = static_cast<float>(src.scale * share);
            }
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

}  // namespace cg::algo
