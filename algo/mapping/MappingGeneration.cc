// The mapper's chunked generation: a frame's cloud particles (Eq. 10) made chunk by chunk in
// parallel from the source table, into per-thread buffers or frame arrays, the same bits for
// any thread count. Declared in Mapping.h.

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "algo/mapping/Mapping.h"
#include "algo/mapping/MappingInternal.h"

namespace cg::algo {

using mapping::checkLibrary;
using mapping::drifts;
using mapping::originsWithDrift;
using mapping::viewOf;

namespace {

/// What every chunk of frame t needs: where each source's copy stands (copyOrigin: Eq. 12's
/// origin plus its drift; zero before the source starts) and the prefix sums of the cluster
/// sizes (Eq. 13), so particle q belongs to the source j with offset[j] <= q < offset[j + 1].
/// With motion asked for, the copies' velocities and the first stable id of each copy too.
struct FramePlan {
    std::vector<float> copyOrigins;
    std::vector<std::uint64_t> offset;
    std::vector<float> copyVelocities;  ///< empty unless velocities are asked for
    std::vector<std::uint64_t> idBase;  ///< empty unless ids are asked for
    std::uint64_t total() const { return offset.back(); }
};

FramePlan planFrame(const SourceTable& table, int frame, const CondensationView& c,
                    const PrimitiveLibrary& lib, const MappingSettings& s,
                    const CloudChunkOptions& o = {})
{
    checkLibrary(lib, s);
    FramePlan plan;
    plan.copyOrigins = originsWithDrift(table, frame, c, lib, s, drifts(lib)).copy;
    if (o.velocities) plan.copyVelocities = copyVelocities(table, frame, c, lib, s);
    if (o.ids) plan.idBase = particleIdBases(table, lib, s);
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
               std::size_t stride, const float* origin, CopyScale scale, std::uint64_t n,
               float* __restrict out)
{
    const std::size_t step = 3 * (K != 0 ? K : stride);
    const float ox = origin[0], oy = origin[1], oz = origin[2];
    const float across = scale.across, up = scale.up;
    if (!lerp) {
        for (std::uint64_t i = 0; i < n; ++i) {
            const float* q = a + i * step;
            out[3 * i] = ox + across * q[0];
            out[3 * i + 1] = oy + across * q[1];
            out[3 * i + 2] = oz + up * q[2];
        }
        return;
    }
    for (std::uint64_t i = 0; i < n; ++i) {
        const float* qa = a + i * step;
        const float* qb = b + i * step;
        out[3 * i] = ox + across * (qa[0] + w * (qb[0] - qa[0]));
        out[3 * i + 1] = oy + across * (qa[1] + w * (qb[1] - qa[1]));
        out[3 * i + 2] = oz + up * (qa[2] + w * (qb[2] - qa[2]));
    }
}

/// Eq. 10 for particles [i0, i1) of the copy of `src` that stands at `origin` (copyOrigin).
void sourceSlice(const Source& src, const float* origin, int frame, const PrimitiveView& p,
                 const MappingSettings& s, std::uint32_t stride, std::uint64_t i0, std::uint64_t i1,
                 float* __restrict out)
{
    const double time = primitiveTime(src, frame, s, p);
    const CopyScale scale = copyScale(src, s);
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

/// particleVelocity for particles [i0, i1) of the copy of `src` moving at `copyVelocity`.
void velocitySlice(const Source& src, const float* copyVelocity, int frame, const PrimitiveView& p,
                   const MappingSettings& s, std::uint32_t stride, std::uint64_t i0,
                   std::uint64_t i1, float* __restrict out)
{
    for (std::uint64_t q = i0; q < i1; ++q)
        particleVelocity(src, copyVelocity, copyFluidId(src, q, stride), frame, p, s,
                         out + 3 * (q - i0));
}

/// What fillRange writes besides the positions; each null when not asked for.
struct ChunkFields {
    std::uint8_t* levels = nullptr;
    std::uint32_t* sources = nullptr;
    float* velocities = nullptr;
    std::uint32_t* ids = nullptr;
};

/// Particles [first, last) of the frame into xyz (and levels / sources when not null), source
/// slice by source slice.
void fillRange(const FramePlan& plan, const SourceTable& table, int frame,
               const PrimitiveLibrary& lib, const MappingSettings& s, std::uint64_t first,
               std::uint64_t last, float* xyz, const ChunkFields& out)
{
    const auto& offset = plan.offset;
    auto j = static_cast<std::size_t>(std::upper_bound(offset.begin(), offset.end(), first) -
                                      offset.begin() - 1);
    for (std::uint64_t q = first; q < last; ++j) {
        const std::uint64_t end = std::min(last, offset[j + 1]);
        if (end == q) continue;  // a source not started yet: no cluster, no frame to look up
        const Source& src = table.sources[j];
        const PrimitiveView& p = viewOf(lib, j, s);
        const std::uint32_t stride = copyStride(s, p);
        sourceSlice(src, &plan.copyOrigins[3 * j], frame, p, s, stride, q - offset[j],
                    end - offset[j], xyz + 3 * (q - first));
        if (out.levels != nullptr) std::fill_n(out.levels + (q - first), end - q, src.level);
        if (out.sources != nullptr)
            std::fill_n(out.sources + (q - first), end - q, static_cast<std::uint32_t>(j));
        if (out.velocities != nullptr)
            velocitySlice(src, &plan.copyVelocities[3 * j], frame, p, s, stride, q - offset[j],
                          end - offset[j], out.velocities + 3 * (q - first));
        if (out.ids != nullptr)
            for (std::uint64_t k = q; k < end; ++k)
                out.ids[k - first] = static_cast<std::uint32_t>(plan.idBase[j] + (k - offset[j]));
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
    if (direct ? (o.levels && o.levelsOut == nullptr) || (o.sources && o.sourcesOut == nullptr) ||
                     o.velocities || o.ids
               : o.levelsOut != nullptr || o.sourcesOut != nullptr)
        throw std::invalid_argument(
            "forEachCloudChunk: frame arrays must be given for every requested field");
    const std::uint64_t total = plan.total();
    const std::uint64_t chunks = total / size + (total % size != 0);
    struct Buffers {
        std::vector<float> xyz;
        std::vector<std::uint8_t> levels;
        std::vector<std::uint32_t> sources;
        std::vector<float> velocities;
        std::vector<std::uint32_t> ids;
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
                              ChunkFields fields;
                              if (direct) {
                                  xyz = o.positionsOut + 3 * chunk.first;
                                  if (o.levels) fields.levels = o.levelsOut + chunk.first;
                                  if (o.sources) fields.sources = o.sourcesOut + chunk.first;
                              } else {
                                  Buffers& b = perThread.local();
                                  if (b.xyz.empty()) {
                                      b.xyz.resize(3 * size);
                                      if (o.levels) b.levels.resize(size);
                                      if (o.sources) b.sources.resize(size);
                                      if (o.velocities) b.velocities.resize(3 * size);
                                      if (o.ids) b.ids.resize(size);
                                  }
                                  xyz = b.xyz.data();
                                  if (o.levels) fields.levels = b.levels.data();
                                  if (o.sources) fields.sources = b.sources.data();
                                  if (o.velocities) fields.velocities = b.velocities.data();
                                  if (o.ids) fields.ids = b.ids.data();
                              }
                              fillRange(plan, table, frame, lib, s, chunk.first,
                                        chunk.first + chunk.count, xyz, fields);
                              if (consume) {
                                  chunk.positions = xyz;
                                  chunk.levels = fields.levels;
                                  chunk.sources = fields.sources;
                                  chunk.velocities = fields.velocities;
                                  chunk.ids = fields.ids;
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
    const FramePlan plan = planFrame(table, frame, c, lib, s, options);
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
