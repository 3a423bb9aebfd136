#include "algo/mapping/Dissipation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "algo/CounterRandom.h"

namespace cg::algo {

namespace {

/// The stream of the particles' edge jitter.
constexpr std::uint64_t kJitterStream = std::uint64_t{1} << 44;

/// Share of the primitive's particles within the radius a copy's edge is measured by.
constexpr double kRadiusQuantile = 0.95;

/// Each particle's distance is scaled by 1 +- this, drawn by its id, so a decaying cloud
/// frays instead of shrinking as a smooth ball.
constexpr double kJitter = 0.25;

/// Centroid and radius of the first n particles of one primitive frame.
std::array<float, 4> frameExtent(const float* xyz, std::uint32_t n)
{
    if (n == 0) return {0.0f, 0.0f, 0.0f, 0.0f};
    double c[3] = {0.0, 0.0, 0.0};
    for (std::uint32_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) c[k] += xyz[3 * i + k];
    for (double& v : c) v /= n;
    std::vector<double> distance(n);
    for (std::uint32_t i = 0; i < n; ++i)
        distance[i] = std::hypot(xyz[3 * i] - c[0], xyz[3 * i + 1] - c[1], xyz[3 * i + 2] - c[2]);
    const auto q = distance.begin() + static_cast<std::ptrdiff_t>(kRadiusQuantile * (n - 1));
    std::nth_element(distance.begin(), q, distance.end());
    return {static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2]),
            static_cast<float>(*q)};
}

/// The frame a cloud starts to decay and how many frames it takes, from its level 1 copy.
struct Decay {
    double start = 0.0;
    double frames = 0.0;
};

Decay rootDecay(const Source& root, const PrimitiveView& p, const MappingSettings& s,
                const DissipationSettings& d)
{
    // Its primitive's last frame is reached at t0 + last ds / (A dt) (Eq. 11).
    const double grown =
        root.startFrame + (p.frameCount - 1) * p.frameTime / (root.speed * s.timeStep);
    const double relative = s.scaleCoefficient > 0.0 ? root.scale / s.scaleCoefficient : 1.0;
    return {grown + d.hold / s.timeStep, d.decayTime * relative / s.timeStep};
}

}  // namespace

void checkDissipation(const DissipationSettings& d)
{
    if (!(d.hold >= 0.0) || !std::isfinite(d.hold))
        throw std::invalid_argument("dissipation: hold must be a finite time >= 0");
    if (!(d.decayTime >= 0.0) || !std::isfinite(d.decayTime))
        throw std::invalid_argument("dissipation: decayTime must be a finite time >= 0");
    if (!(d.anvilBase >= 0.0) || !std::isfinite(d.anvilBase))
        throw std::invalid_argument("dissipation: anvilBase must be a finite height >= 0");
    if (!(d.anvilLife >= 1.0) || !std::isfinite(d.anvilLife))
        throw std::invalid_argument("dissipation: anvilLife must be a finite factor >= 1");
}

PrimitiveExtent primitiveExtent(const PrimitiveView& p)
{
    PrimitiveExtent out;
    out.frames.reserve(static_cast<std::size_t>(std::max(p.frameCount, 0)));
    for (int f = 0; f < p.frameCount; ++f)
        out.frames.push_back(frameExtent(p.frames[f], p.counts[f]));
    return out;
}

std::vector<float> cloudDecay(const SourceTable& table, int frame, const PrimitiveLibrary& lib,
                              const MappingSettings& s, const DissipationSettings& d)
{
    checkDissipation(d);
    std::vector<float> decay(table.sources.size(), 0.0f);
    std::vector<std::uint32_t> root(table.sources.size());
    // Parents precede children: a child's cloud is its parent's.
    for (std::size_t j = 0; j < table.sources.size(); ++j) {
        const Source& src = table.sources[j];
        root[j] = src.level == 1 ? static_cast<std::uint32_t>(j) : root[src.parent];
        if (root[j] != j) {
            decay[j] = decay[root[j]];
            continue;
        }
        const Decay c = rootDecay(src, lib.views[primitiveOf(j, s)], s, d);
        const double past = frame - c.start;
        decay[j] = past <= 0.0         ? 0.0f
                   : !(c.frames > 0.0) ? 1e9f  // decays at once
                                       : static_cast<float>(past / c.frames);
    }
    return decay;
}

CloudChunk chunkSurviving(const CloudChunk& chunk, const DissipationFrame& d, KeptParticles& kept)
{
    if (chunk.sources == nullptr || chunk.ids == nullptr || chunk.copyOrigins == nullptr)
        throw std::invalid_argument("dissipation: the chunk carries no sources, ids or origins");
    kept.positions.clear();
    kept.levels.clear();
    kept.sources.clear();
    kept.velocities.clear();
    kept.ids.clear();
    const MappingSettings& s = *d.settings;
    std::uint32_t last = 0xFFFFFFFFu;
    float f = 0.0f;
    CopyScale r{1.0f, 1.0f};
    std::array<float, 4> extent{};
    const float* o = nullptr;  // the run's copy origin
    for (std::uint64_t i = 0; i < chunk.count; ++i) {
        const std::uint32_t j = chunk.sources[i];
        if (j != last) {  // particles come in runs of one source
            last = j;
            const Source& src = d.table->sources[j];
            // A cloud's turrets go before its body: level L decays L times as fast; the
            // anvil's ice lasts anvilLife times longer.
            o = chunk.copyOrigins + 3 * std::size_t{j};
            const bool anvil = d.dissipation.anvilBase > 0.0 && o[2] >= d.dissipation.anvilBase;
            const double life = anvil ? d.dissipation.anvilLife : 1.0;
            f = static_cast<float>(std::min(1.0, d.decay[j] * src.level / life));
            const std::size_t primitive = primitiveOf(j, s);
            const PrimitiveView& p = d.library->views[primitive];
            const double time =
                std::min(std::floor(primitiveTime(src, d.frame, s, p)), p.frameCount - 1.0);
            extent = d.extents[primitive].frames[static_cast<std::size_t>(std::max(time, 0.0))];
            r = copyScale(src, s);
        }
        if (f >= 1.0f) continue;
        if (f > 0.0f) {
            const float* x = chunk.positions + 3 * i;
            const double dx = (x[0] - o[0]) / r.across - extent[0],
                         dy = (x[1] - o[1]) / r.across - extent[1],
                         dz = (x[2] - o[2]) / r.up - extent[2];
            const double edge = std::sqrt(dx * dx + dy * dy + dz * dz) / extent[3];
            const double jitter =
                1.0 + kJitter * (2.0 * counterUniform(s.seed, kJitterStream, chunk.ids[i]) - 1.0);
            if (!(edge * jitter < 1.0 - f)) continue;
        }
        kept.positions.insert(kept.positions.end(), chunk.positions + 3 * i,
                              chunk.positions + 3 * i + 3);
        if (chunk.levels) kept.levels.push_back(chunk.levels[i]);
        kept.sources.push_back(j);
        if (chunk.velocities)
            kept.velocities.insert(kept.velocities.end(), chunk.velocities + 3 * i,
                                   chunk.velocities + 3 * i + 3);
        kept.ids.push_back(chunk.ids[i]);
    }
    CloudChunk out = chunk;
    out.count = kept.positions.size() / 3;
    out.positions = kept.positions.data();
    out.levels = chunk.levels ? kept.levels.data() : nullptr;
    out.sources = kept.sources.data();
    out.velocities = chunk.velocities ? kept.velocities.data() : nullptr;
    out.ids = kept.ids.data();
    return out;
}

}  // namespace cg::algo
