// The mapper's motion: the velocities of copies and cloud particles (Eq. 10-12 differentiated
// in time) and the particles' stable ids, for motion blur and for trails across frames.
// Declared in Mapping.h.

#include <cmath>
#include <limits>
#include <stdexcept>

#include "algo/mapping/Mapping.h"
#include "algo/mapping/MappingInternal.h"

namespace cg::algo {

using mapping::viewOf;

namespace {

/// Primitive frames per second of src's copy: ds/dt of Eq. 11, A / ds.
double primitiveRate(const Source& src, const PrimitiveView& p) { return src.speed / p.frameTime; }

/// The velocity of a level 1 source's origin: its condensation particle's (Eq. 12), without
/// the rise when the copy stands on the condensation level, none when a Trail copy was laid.
void level1OriginVelocity(const SourceTable& table, std::size_t j, const CondensationView& c,
                          const MappingSettings& s, float out[3])
{
    const std::uint32_t k = table.sources[j].parent;
    const bool laid = s.level1Origin == Level1Origin::Trail && !std::isnan(table.anchors[3 * j]);
    const bool rises = s.level1Origin != Level1Origin::CondensationLevel;
    out[0] = laid || c.vx == nullptr ? 0.0f : c.vx[k];
    out[1] = laid || c.vy == nullptr ? 0.0f : c.vy[k];
    out[2] = laid || !rises || c.vz == nullptr ? 0.0f : c.vz[k];
}

/// What the drift past the primitive's end adds to a copy's velocity: d/dt of copyShift's
/// R drift tau (1 - exp(-past / tau)).
void driftVelocity(const Source& src, const PrimitiveView& p, const MappingSettings& s,
                   const float drift[3], int frame, float out[3])
{
    const double past = primitiveTime(src, frame, s, p) - (p.frameCount - 1);
    const bool drifting = s.pastLastFrame == PastLastFrame::Drift && past > 0.0;
    const double rate =
        drifting ? std::exp(-past / kDriftDecayFrames) * primitiveRate(src, p) : 0.0;
    const CopyScale r = copyScale(src, s);
    for (int k = 0; k < 3; ++k)
        out[k] = static_cast<float>(rate * (k < 2 ? r.across : r.up) * drift[k]);
}

}  // namespace

void particleVelocity(const Source& src, const float* copyVelocity, std::uint32_t i, int frame,
                      const PrimitiveView& p, const MappingSettings& s, float out[3])
{
    const double time = primitiveTime(src, frame, s, p);
    const double whole = std::floor(time);
    for (int k = 0; k < 3; ++k) out[k] = copyVelocity[k];
    if (whole >= p.frameCount - 1) return;  // the last shape holds
    const int f = static_cast<int>(whole);
    const float* a = p.frames[f] + 3 * static_cast<std::size_t>(i);
    const float* b = p.frames[f + 1] + 3 * static_cast<std::size_t>(i);
    const auto rate = static_cast<float>(primitiveRate(src, p));
    const CopyScale r = copyScale(src, s);
    for (int k = 0; k < 3; ++k) out[k] += rate * (k < 2 ? r.across : r.up) * (b[k] - a[k]);
}

std::vector<float> copyVelocities(const SourceTable& table, int frame, const CondensationView& c,
                                  const PrimitiveLibrary& lib, const MappingSettings& s)
{
    mapping::checkLibrary(lib, s);
    const mapping::Drifts drift = mapping::drifts(lib);
    std::vector<float> out(3 * table.sources.size(), 0.0f);
    // In table order: a parent's copy velocity is known before its children read it.
    for (std::size_t j = 0; j < table.sources.size(); ++j) {
        const Source& src = table.sources[j];
        if (frame < src.startFrame) continue;
        float origin[3];
        if (src.level == 1) {
            level1OriginVelocity(table, j, c, s, origin);
        } else {
            particleVelocity(table.sources[src.parent], &out[3 * std::size_t{src.parent}],
                             src.parentFluid, frame, viewOf(lib, src.parent, s), s, origin);
        }
        const std::size_t primitive = primitiveOf(j, s);
        float shift[3];
        driftVelocity(src, lib.views[primitive], s, drift[primitive].data(), frame, shift);
        for (int k = 0; k < 3; ++k) out[3 * j + k] = origin[k] + shift[k];
    }
    return out;
}

std::vector<std::uint64_t> particleIdBases(const SourceTable& table, const PrimitiveLibrary& lib,
                                           const MappingSettings& s)
{
    mapping::checkLibrary(lib, s);
    // A copy's largest cluster: its thinned N_f at the primitive frame with the most particles.
    std::vector<std::uint32_t> most(lib.views.size(), 0);
    for (std::size_t v = 0; v < lib.views.size(); ++v)
        for (int f = 0; f < lib.views[v].frameCount; ++f)
            most[v] = std::max(most[v], lib.views[v].counts[f]);
    std::vector<std::uint64_t> base(table.sources.size() + 1, 0);
    for (std::size_t j = 0; j < table.sources.size(); ++j) {
        const PrimitiveView& p = viewOf(lib, j, s);
        const std::uint32_t n = most[primitiveOf(j, s)];
        const std::uint32_t k = copyStride(s, p);
        const std::uint32_t phase = table.sources[j].phase;
        base[j + 1] = base[j] + (n > phase ? (n - phase + k - 1) / k : 0);
    }
    if (base.back() > std::numeric_limits<std::uint32_t>::max())
        throw std::invalid_argument("the mapping's particles need " + std::to_string(base.back()) +
                                    " ids, more than 32-bit ids can name");
    base.pop_back();
    return base;
}

}  // namespace cg::algo
