// What a stored source table must satisfy before the mapping algorithm may read it.

#include <cmath>
#include <string>
#include <vector>

#include "nodes/data/CloudParticles.h"
#include "nodes/data/CloudSources.h"
#include "nodes/data/PrimitiveSet.h"
#include "nodes/data/ValueChecks.h"
#include "nodes/data/VapourParticles.h"

namespace cg {

namespace {

constexpr const char* kType = "CloudSources";

std::string record(std::size_t j) { return "record " + std::to_string(j) + ": "; }

void checkSettings(const algo::MappingSettings& s)
{
    using L = MappingLimits;
    // Eq. 14 picks floor(M candidates) among the candidates: M > 1 would ask for more than
    // there are, and the probing for a free one would never end.
    if (s.selectionRatio.empty() || s.selectionRatio.size() > L::kMaxListSize)
        checks::refuse(kType, std::to_string(s.selectionRatio.size()) + " selection ratios");
    for (double m : s.selectionRatio) checks::finiteIn(m, 0.0, 1.0, kType, "selection ratio");
    if (s.windowLength.empty() || s.windowLength.size() > L::kMaxListSize)
        checks::refuse(kType, std::to_string(s.windowLength.size()) + " window lengths");
    for (int w : s.windowLength)
        checks::intIn(static_cast<std::uint64_t>(std::int64_t{w}), 0, L::kMaxFrames, kType,
                      "window length");
}

/// t_s[L] = t_s[1] + (L - 1) chi for every level, all -1 before t_s[1] is known; t_s[1] is
/// firstStart when that is set.
void checkLevelStarts(const algo::SourceTable& t, const algo::MappingSettings& s)
{
    if (t.levelStart.size() != static_cast<std::size_t>(s.maxLevel))
        checks::refuse(kType, std::to_string(t.levelStart.size()) + " level starts for " +
                                  std::to_string(s.maxLevel) + " levels");
    const std::int64_t first = t.levelStart[0];
    if (first < -1 || first > checks::kMaxFrame || (s.firstStart >= 0 && first != s.firstStart))
        checks::refuse(kType, "t_s[1] = " + std::to_string(first) + " is not one the mapper makes");
    for (std::size_t l = 0; l < t.levelStart.size(); ++l) {
        const std::int64_t expected =
            first < 0 ? -1 : first + static_cast<std::int64_t>(l) * s.levelDelay;
        if (t.levelStart[l] != expected)
            checks::refuse(kType, "t_s[" + std::to_string(l + 1) +
                                      "] = " + std::to_string(t.levelStart[l]) + ", not " +
                                      std::to_string(expected));
    }
}

/// One record against the records before it (parents precede children).
void checkRecord(const algo::SourceTable& t, const algo::MappingSettings& s, std::size_t j)
{
    const algo::Source& src = t.sources[j];
    if (src.level < 1 || src.level > t.topLevel)
        checks::refuse(kType, record(j) + "level " + std::to_string(src.level) + " is outside 1.." +
                                  std::to_string(t.topLevel));
    // Records are appended frame by frame.
    if (j > 0 && src.startFrame < t.sources[j - 1].startFrame)
        checks::refuse(kType, record(j) + "starts before the record above it");
    // Eq. 16 with fNoise in [0, 1]: A = 1 + A0 fNoise, R = R0 fNoise. A >= 1 keeps the
    // primitive time s = A (t - t0) dt / ds from running backwards to negative frames.
    const auto maxSpeed = static_cast<float>(1.0 + s.speedCoefficient);
    const auto maxScale = static_cast<float>(s.scaleCoefficient);
    if (!(src.speed >= 1.0f && src.speed <= maxSpeed))
        checks::refuse(kType, record(j) + "speed " + std::to_string(src.speed) +
                                  " is outside [1, " + std::to_string(maxSpeed) + "]");
    if (!(src.scale >= 0.0f && src.scale <= maxScale))
        checks::refuse(kType, record(j) + "scale " + std::to_string(src.scale) +
                                  " is outside [0, " + std::to_string(maxScale) + "]");
    // cloudTop 'spread' flattens a copy to at least kSmallestCappedScale of its height.
    if (!(src.flatten >= static_cast<float>(algo::kSmallestCappedScale) && src.flatten <= 1.0f))
        checks::refuse(kType, record(j) + "flatten " + std::to_string(src.flatten) +
                                  " is outside [" + std::to_string(algo::kSmallestCappedScale) +
                                  ", 1]");
    // Unthinned copies carry every fluid id: no phase.
    if (s.particlesPerCopy == 0 && src.phase != 0)
        checks::refuse(kType, record(j) + "has a phase but copies are not thinned");
    if (src.level == 1) {
        if (src.parentFluid != 0)
            checks::refuse(kType, record(j) + "level 1 with a parent fluid id");
        return;
    }
    // Eq. 12: a level-L record sits on a cloud particle of an earlier level-(L-1) record, so
    // (records being in start order) one that had started: the parent's primitive time is
    // never negative where the child reads it.
    if (src.parent >= j)
        checks::refuse(kType,
                       record(j) + "parent " + std::to_string(src.parent) + " does not precede it");
    if (t.sources[src.parent].level + 1 != src.level)
        checks::refuse(kType, record(j) + "parent is not one level below");
}

/// Every level-1 parent is a taken condensation particle, each once; a taken particle without
/// a record is one the cloud top refused a copy (the selection bounds its draws by the free
/// particles, so their number does not matter).
void checkCondensationTaken(const algo::SourceTable& t)
{
    std::vector<std::uint8_t> seen(t.condensationTaken.size(), 0);
    std::size_t taken = 0;
    for (std::uint8_t v : t.condensationTaken) {
        if (v > 1)
            checks::refuse(kType, "a condensation particle's taken flag is " + std::to_string(v));
        taken += v;
    }
    std::size_t levelOne = 0;
    for (std::size_t j = 0; j < t.sources.size(); ++j) {
        const algo::Source& src = t.sources[j];
        if (src.level != 1) continue;
        ++levelOne;
        if (src.parent >= seen.size() || t.condensationTaken[src.parent] == 0)
            checks::refuse(kType, record(j) + "its condensation particle is not marked taken");
        if (seen[src.parent]++ != 0)
            checks::refuse(kType, record(j) + "its condensation particle is taken twice");
    }
    if (taken < levelOne)
        checks::refuse(kType, std::to_string(taken) + " condensation particles taken for " +
                                  std::to_string(levelOne) + " level-1 records");
}

/// The cloud particles taken (j' << 32 | q, sorted, each once) name records, at least one per
/// deeper record on that record's parent j' (more where the cloud top refused copies).
void checkCloudTaken(const algo::SourceTable& t)
{
    const std::size_t n = t.sources.size();
    std::vector<std::int64_t> balance(n, 0);  // children of j' minus keys naming j'
    std::size_t deeper = 0;
    for (const algo::Source& src : t.sources)
        if (src.level >= 2) ++deeper, ++balance[src.parent];
    if (t.cloudTaken.size() < deeper)
        checks::refuse(kType, std::to_string(t.cloudTaken.size()) + " cloud particles taken for " +
                                  std::to_string(deeper) + " records of level 2 or more");
    for (std::size_t i = 0; i < t.cloudTaken.size(); ++i) {
        const std::uint64_t key = t.cloudTaken[i];
        if (i > 0 && key <= t.cloudTaken[i - 1])
            checks::refuse(kType, "taken cloud particles are not sorted and distinct");
        const std::uint64_t owner = key >> 32;
        if (owner >= n)
            checks::refuse(kType, "taken cloud particle of record " + std::to_string(owner) +
                                      " names no record");
        --balance[owner];
    }
    for (std::size_t j = 0; j < n; ++j)
        if (balance[j] > 0)
            checks::refuse(kType, "record " + std::to_string(j) + " has " +
                                      std::to_string(balance[j]) +
                                      " children on cloud particles not marked taken");
}

/// Trail copies' anchors: 3 floats per record with Level1Origin::Trail, none otherwise, so an
/// origin is never read past the array: a level 1 record's are all finite (laid) or all NaN
/// (riding its particle), a deeper record's zero.
void checkAnchors(const algo::SourceTable& t, const algo::MappingSettings& s)
{
    const bool trail = s.level1Origin == algo::Level1Origin::Trail;
    const std::size_t expected = trail ? 3 * t.sources.size() : 0;
    if (t.anchors.size() != expected)
        checks::refuse(kType, std::to_string(t.anchors.size()) + " anchor values for " +
                                  std::to_string(expected / 3) + " trail records");
    for (std::size_t j = 0; j < expected / 3; ++j) {
        const float* a = &t.anchors[3 * j];
        const bool riding = std::isnan(a[0]) && std::isnan(a[1]) && std::isnan(a[2]);
        const bool laid = std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2]);
        const bool fits =
            t.sources[j].level == 1 ? riding || laid : a[0] == 0.0f && a[1] == 0.0f && a[2] == 0.0f;
        if (!fits)
            checks::refuse(kType, record(j) + "anchor (" + std::to_string(a[0]) + ", " +
                                      std::to_string(a[1]) + ", " + std::to_string(a[2]) +
                                      ") does not fit a level " +
                                      std::to_string(t.sources[j].level) + " record");
    }
}

}  // namespace

void checkSourceTable(const algo::SourceTable& t, const algo::MappingSettings& s)
{
    checkSettings(s);
    if (t.topLevel < 1 || t.topLevel > s.maxLevel)
        checks::refuse(kType, "L_max " + std::to_string(t.topLevel) + " is outside 1.." +
                                  std::to_string(s.maxLevel));
    if (t.sources.size() > s.maxSources)
        checks::refuse(kType, std::to_string(t.sources.size()) + " records, over maxSources");
    checkLevelStarts(t, s);
    for (std::size_t j = 0; j < t.sources.size(); ++j) checkRecord(t, s, j);
    checkCondensationTaken(t);
    checkCloudTaken(t);
    checkAnchors(t, s);
}

void checkSourcesFit(const algo::SourceTable& t, const algo::MappingSettings& s,
                     const CondensationData& condensation,
                     const std::vector<std::shared_ptr<const PrimitiveSetData>>& primitives)
{
    if (primitives.size() != s.primitiveCount)
        checks::refuse(kType, "made with " + std::to_string(s.primitiveCount) +
                                  " primitive sets, given " + std::to_string(primitives.size()));
    for (std::size_t j = 0; j < t.sources.size(); ++j) {
        const algo::Source& src = t.sources[j];
        if (src.level == 1) {
            // Selected among the particles condensed by its start frame.
            if (src.parent >= condensation.condensedFrame.size())
                checks::refuse(kType, record(j) + "condensation particle " +
                                          std::to_string(src.parent) + " does not exist");
            const std::int32_t condensed = condensation.condensedFrame[src.parent];
            if (condensed < 0 || condensed > src.startFrame)
                checks::refuse(
                    kType, record(j) + "condensation particle had not condensed when it started");
            continue;
        }
        // Drawn among the parent copy's particles at the start frame: fluid ids below N_f there,
        // so below N_f at every later frame (A >= 1, N_f never decreases).
        if (src.parent >= j) checks::refuse(kType, record(j) + "parent does not precede it");
        const algo::Source& parent = t.sources[src.parent];
        // The parent's particles are those of the primitive it plays.
        const PrimitiveSetData& primitive = *primitives[algo::primitiveOf(src.parent, s)];
        algo::PrimitiveView p;
        p.counts = primitive.counts.data();
        p.frameCount = primitive.frames();
        p.frameTime = primitive.frameTime;
        if (p.frameCount == 0) checks::refuse(kType, "the primitive set has no frames");
        const double time = std::floor(algo::primitiveTime(parent, src.startFrame, s, p));
        if (!(time >= 0.0))
            checks::refuse(kType, record(j) + "its parent's primitive time is negative");
        const int index = time < p.frameCount - 1 ? static_cast<int>(time) : p.frameCount - 1;
        if (src.parentFluid >= primitive.count(index))
            checks::refuse(kType, record(j) + "parent fluid particle " +
                                      std::to_string(src.parentFluid) + " is not in the primitive");
    }
}

void checkSourcesFit(const algo::SourceTable& t, const algo::MappingSettings& s,
                     const CondensationData& condensation, const PrimitiveSetData& primitive)
{
    // A non-owning pointer (the aliasing constructor with no owner): the caller keeps it alive.
    const std::shared_ptr<const PrimitiveSetData> one(std::shared_ptr<void>(), &primitive);
    checkSourcesFit(t, s, condensation, {one});
}

}  // namespace cg
