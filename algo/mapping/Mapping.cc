// The mapper's formulas: the times, cluster sizes and positions of Eq. 10-13 and the sources'
// origins (Eq. 12). Selecting the sources is MappingSources.cc's job, generating a frame's
// particles chunk by chunk MappingGeneration.cc's.

#include "algo/mapping/Mapping.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "algo/CounterRandom.h"
#include "algo/mapping/MappingInternal.h"

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

namespace mapping {

/// Refuses a library that is not the one the settings' table was made with.
void checkLibrary(const PrimitiveLibrary& lib, const MappingSettings& s)
{
    if (lib.views.size() != s.primitiveCount)
        throw std::invalid_argument("the mapping was made with " +
                                    std::to_string(s.primitiveCount) + " primitives, not " +
                                    std::to_string(lib.views.size()));
}

Drifts drifts(const PrimitiveLibrary& lib)
{
    Drifts out(lib.views.size());
    for (std::size_t i = 0; i < lib.views.size(); ++i) primitiveDrift(lib.views[i], out[i].data());
    return out;
}

}  // namespace mapping

using mapping::viewOf;

std::size_t primitiveOf(std::size_t j, const MappingSettings& s)
{
    if (s.primitiveCount <= 1) return 0;
    return static_cast<std::size_t>(counterBits(s.seed, mapping::kPrimitiveStream, j) %
                                    s.primitiveCount);
}

CopyScale copyScale(const Source& src, const MappingSettings& s)
{
    const double r = s.metresPerPrimitiveMetre * src.scale;
    const double flatten = src.flatten > 0.0f ? src.flatten : 1.0;
    return {static_cast<float>(r / std::sqrt(flatten)), static_cast<float>(r * flatten)};
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
    const CopyScale scale = copyScale(src, s);
    float shift[3];
    copyShift(p, s, drift, time, shift);
    for (int k = 0; k < 3; ++k)
        out[k] = sourceOrigin[k] + (k < 2 ? scale.across : scale.up) * shift[k];
}

}  // namespace

namespace mapping {

void cloudParticlePosition(const Source& src, const float* copyAt, std::uint32_t i, int frame,
                           const PrimitiveView& p, const MappingSettings& s, float out[3])
{
    float f[3];
    primitivePosition(p, i, primitiveTime(src, frame, s, p), f);
    const CopyScale r = copyScale(src, s);
    for (int k = 0; k < 3; ++k) out[k] = copyAt[k] + (k < 2 ? r.across : r.up) * f[k];
}

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

}  // namespace mapping

std::vector<float> sourceOrigins(const SourceTable& table, int frame, const CondensationView& c,
                                 const PrimitiveLibrary& lib, const MappingSettings& s)
{
    mapping::checkLibrary(lib, s);
    return mapping::originsWithDrift(table, frame, c, lib, s, mapping::drifts(lib)).origin;
}

std::vector<std::uint64_t> cloudCounts(const SourceTable& table, int frame,
                                       const PrimitiveLibrary& lib, const MappingSettings& s)
{
    mapping::checkLibrary(lib, s);
    std::vector<std::uint64_t> counts(static_cast<std::size_t>(std::max(s.maxLevel, 1)), 0);
    for (std::size_t j = 0; j < table.sources.size(); ++j) {
        const Source& src = table.sources[j];
        if (src.level >= 1 && src.level <= counts.size())
            counts[src.level - 1u] += clusterSize(src, frame, s, viewOf(lib, j, s));
    }
    return counts;
}

}  // namespace cg::algo
