#pragma once
/// Recursive mapping of the cloud primitive set (Sec. 5.2, Eq. 10-16), node-free.
///
/// The mapper keeps only a table of source records; cloud particles are a pure function of
/// that table, the condensation particles at frame t and the primitive set, so they are
/// generated on demand for one frame at a time and never stored for all frames.
///
/// Times: t and t0 are stochastic frames. A source started at t0 plays the primitive at
/// primitive frame s = A (t - t0) dt / ds (Eq. 11 with the stochastic time step dt and the
/// primitive's frame time ds; the paper uses dt = ds). N_f at a fractional s is N_f(floor s)
/// (particles appear at whole primitive frames); a particle's position at fractional s is
/// interpolated linearly between frames floor s and floor s + 1. Past the primitive's last
/// frame a copy keeps its last shape and, by default, drifts on as a whole with the
/// primitive's mean motion over its last frames (PastLastFrame).
///
/// Implemented in three files: Mapping.cc (the formulas and origins), MappingSources.cc
/// (stepSources) and MappingGeneration.cc (forEachCloudChunk, generateCloudParticles).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <type_traits>
#include <vector>

#include "util/HugePages.h"

namespace cg::algo {

/// One source record j: what Eq. 10-12 and 16 need to place its cluster at any frame.
struct Source {
    std::uint8_t level = 1;    ///< L
    std::uint16_t phase = 0;   ///< o_j: the copy's first fluid id when copies are thinned
    std::uint32_t parent = 0;  ///< L = 1: condensation particle index; L >= 2: source index j'
    std::uint32_t parentFluid =
        0;                        ///< L >= 2: fluid particle id i' (in the primitive) of the parent
    std::int32_t startFrame = 0;  ///< t0[L, j]
    float speed = 1.0f;           ///< A[L, j] = 1 + A0 fNoise (Eq. 16)
    float scale = 0.0f;           ///< R[L, j] = R0 fNoise (Eq. 16)
    /// Ours (cloudTop 'spread'): the copy's height over the paper's, <= 1; it is as much wider,
    /// 1 / sqrt(flatten), so it keeps its volume. 1: the paper's copy.
    float flatten = 1.0f;
};

static_assert(sizeof(Source) == 28, "the source record stays 28 bytes (docs/mapper.md)");

/// The metres a primitive metre of a copy spans across (x, y) and up (z): R times the global
/// scale, spread by the source's flatten.
struct CopyScale {
    float across = 0.0f;
    float up = 0.0f;
};

/// The mapper's whole state at one frame.
struct SourceTable {
    std::vector<Source> sources;           ///< in order of selection; parents precede children
    std::int32_t topLevel = 1;             ///< L_max so far (pseudocode lines 7, 26-27)
    std::vector<std::int32_t> levelStart;  ///< t_s[L] per level (index L-1); -1 while unknown
    /// Condensation particles already selected (index -> 1): each is a source at most once.
    std::vector<std::uint8_t> condensationTaken;
    /// Cloud particles already selected, as (j' << 32 | q), q the particle's index in its
    /// copy, sorted: each at most once.
    std::vector<std::uint64_t> cloudTaken;
    /// With Level1Origin::Trail, 3 floats per source: where a level 1 copy was laid (its
    /// condensation particle's position at its start frame), or three NaNs for a copy that
    /// rides its particle; zero for deeper sources. Empty with the other rules.
    std::vector<float> anchors;
};

/// A read-only view of the primitive set: N_f(s) and frame positions (xyz floats).
struct PrimitiveView {
    const std::uint32_t* counts = nullptr;
    const float* const* frames = nullptr;  ///< frames[s] -> N_f(s) xyz triples
    int frameCount = 0;
    double frameTime = 1.0;  ///< ds, seconds
};

/// The primitive sets copies draw from (ours; the paper maps one): source j's copy plays
/// primitive primitiveOf(j), so neighbouring towers do not share an outline. One view is the
/// paper's case, and converts implicitly.
struct PrimitiveLibrary {
    std::vector<PrimitiveView> views;  ///< at least one

    PrimitiveLibrary(const PrimitiveView& one)
        : views{one} {}  // NOLINT: one primitive is a library
    explicit PrimitiveLibrary(std::vector<PrimitiveView> several);
};

/// At most this many primitives in a library.
inline constexpr std::size_t kMaxPrimitives = 8;

/// A read-only view of the condensation particles at frame t.
struct CondensationView {
    const float* x = nullptr;
    const float* y = nullptr;
    const float* z = nullptr;
    const std::int32_t* condensedFrame = nullptr;  ///< -1 while still vapour
    const float* condensedZ = nullptr;             ///< height at condensation; NaN while vapour
    std::size_t count = 0;
    /// Velocity, m/s: read by Level1Origin::Trail (vz) and for the copies' motion (null: 0).
    const float* vz = nullptr;
    const float* vx = nullptr;
    const float* vy = nullptr;
};

/// A read-only view of the density map fNoise.
struct MapView {
    const float* values = nullptr;
    int nx = 0;
    int ny = 0;
    double cellSize = 1.0;
    float at(double x, double y) const;  ///< fNoise of the cell under (x, y), clamped to the map
};

/// How Eq. 15 picks the parent cloud particle of a level L >= 2 source.
enum class ParentRule : std::uint8_t {
    /// The paper: a level L-1 source r_j uniformly among those with particles, then one of its
    /// N_f(A (t - t0)) particles r_i uniformly; a pair already taken is drawn again.
    PerSource,
    /// Ours: uniformly over all level L-1 cloud particles (which weights a parent by its
    /// cluster size); a taken draw probes forward to the next free particle.
    PerParticle,
};

/// What a copy does past the primitive's last frame (ours; the paper's primitive outlasts its
/// animation, ours is shorter than most copies live).
enum class PastLastFrame : std::uint8_t {
    /// The copy keeps the last frame's shape and moves on as a whole, starting at the
    /// primitive's drift (the mean displacement per frame of its particles over its last
    /// kDriftFrames frames) and slowing down with the time constant kDriftDecayFrames, as a
    /// thermal does that has spent its buoyancy: a grown turret keeps rising, ever slower,
    /// instead of freezing, and rises at most kDriftDecayFrames times the drift.
    Drift,
    /// The last frame holds: a grown copy stands still.
    Hold,
};

/// Where a level 1 copy stands (Eq. 12, L = 1).
enum class Level1Origin : std::uint8_t {
    /// The paper: on its condensation particle, which keeps rising after it condensed.
    Particle,
    /// Ours: below the particle, at the height where it condensed (its condensation level),
    /// following it across the ground. The copy's own primitive already grows upwards from
    /// its base; riding the rising particle as well lifts each copy's base by however far
    /// its particle has risen since, which scatters the bases over hundreds of metres where
    /// a cumulus has a flat one.
    CondensationLevel,
    /// Ours: a copy selected while its particle rises at least trailRiseSpeed is laid where
    /// the particle is and stays there: the rising air leaves its copies behind along its
    /// path. In a steady updraft the cloud stands still in the storm's frame while air flows
    /// through it (Atmosphere windFrame 'storm'), so a cumulonimbus's stem is cloud at every
    /// height the air passed. A copy selected on a particle that has stopped rising (the top
    /// of its tower) rides it, as the paper's do, so the anvil spreads with the outflow.
    Trail,
};

/// Frames over which the drift is measured: long enough to average out the puff's churning.
inline constexpr int kDriftFrames = 10;
/// The drift's decay time, primitive frames (value ours: long enough that the tops of
/// Figures 1 and 7.A still rise in their last tenths with level 1 copies standing on the
/// condensation level).
inline constexpr double kDriftDecayFrames = 60.0;

enum class CloudTopRule { Shrink, Spread };

/// With a cloudTop, the smallest share of its R0 fNoise a copy keeps (value ours): a copy
/// that would be smaller is not made, so no dust of tiny copies piles up under the cap.
inline constexpr double kSmallestCappedScale = 0.1;

struct MappingSettings {
    int maxLevel = 5;                         ///< cap on L_max
    std::vector<double> selectionRatio{0.2};  ///< M[L]; the last value repeats for higher L
    int firstStart = -1;                      ///< t_s[1]; -1: the first condensation frame
    int levelDelay = 50;                      ///< chi: t_s[L] = t_s[L-1] + chi
    std::vector<int> windowLength{100, 60};   ///< t_e[L] - t_s[L]; the last value repeats
    double scaleCoefficient = 1.5;            ///< R0 of Eq. 16
    double speedCoefficient = 2.0;            ///< A0 of Eq. 16
    double metresPerPrimitiveMetre = 1.0;     ///< global scale of every cluster (ours)
    double timeStep = 1.0;                    ///< dt of the stochastic simulation, seconds
    std::uint64_t seed = 0;
    std::uint64_t maxSources = 1u << 24;  ///< selection stops here (a memory guard)
    /// K: when > 0, each copy carries only about K of the primitive's particles (ours): copy j
    /// takes fluid ids o_j, o_j + k, o_j + 2k, ... with k = ceil(N_f(last) / K) and its own
    /// phase o_j in [0, k) drawn at selection, so different copies carry different particles.
    /// 0: every copy carries all N_f(s) (the paper).
    std::uint32_t particlesPerCopy = 0;
    ParentRule parentRule = ParentRule::PerSource;  ///< Eq. 15's draw of a parent particle
    PastLastFrame pastLastFrame = PastLastFrame::Drift;
    Level1Origin level1Origin = Level1Origin::Particle;
    /// With Level1Origin::Trail: the vertical speed (m/s) from which a particle lays its copy
    /// rather than carrying it (value ours: updrafts rise at 5-20 m/s, a tower's top settles
    /// around its equilibrium level at a few m/s).
    double trailRiseSpeed = 3.0;
    /// Ours: the height (m above sea level) no copy may rise past, 0 = none (the paper). A copy
    /// selected with its origin ending up at z may keep the share v = (cloudTop - z) /
    /// (R0 fNoise top) of its height, top the primitive's highest point (its drift's rise
    /// included); one that would keep less than kSmallestCappedScale is not made (its
    /// candidate is used up), the others become what cloudTopRule says. A sounding's
    /// equilibrium level, where thermals stop rising, caps a fair-weather cumulus field.
    double cloudTop = 0.0;
    /// What a copy that would rise past cloudTop becomes: smaller (CloudTopRule::Shrink), or
    /// as wide and flatter, spreading under the cap as air does under an inversion or the
    /// tropopause (CloudTopRule::Spread, an anvil's way).
    CloudTopRule cloudTopRule = CloudTopRule::Shrink;
    /// Primitives in the library the table was made with (1..kMaxPrimitives): source j plays
    /// primitive primitiveOf(j), drawn from the seed by j alone.
    std::uint32_t primitiveCount = 1;
};

/// Source src's CopyScale (Source::flatten).
CopyScale copyScale(const Source& src, const MappingSettings& s);

/// The primitive source j plays: a draw from the seed keyed by j, so it depends on neither the
/// frame nor the thread order; 0 with one primitive (the paper).
std::size_t primitiveOf(std::size_t j, const MappingSettings& s);

/// k, the fluid-id stride of thinned copies: ceil(N_f(last) / K), at least 1, at most 65,536
/// (the phase is 16 bits); 1 when particlesPerCopy is 0.
std::uint32_t copyStride(const MappingSettings& s, const PrimitiveView& p);

double selectionRatio(const MappingSettings& s, int level);
int windowLength(const MappingSettings& s, int level);

/// Primitive frame s of a source at stochastic frame t (Eq. 11).
double primitiveTime(const Source& src, int frame, const MappingSettings& s,
                     const PrimitiveView& p);
/// The copy's particle count at frame t (Eq. 13's N_f(s), thinned): the fluid ids o_j + q k
/// below N_f(s); 0 before its start.
std::uint32_t clusterSize(const Source& src, int frame, const MappingSettings& s,
                          const PrimitiveView& p);
/// Fluid id of particle q of source src's copy: o_j + q k.
inline std::uint32_t copyFluidId(const Source& src, std::uint64_t q, std::uint32_t stride)
{
    return static_cast<std::uint32_t>(src.phase + q * stride);
}
/// Position of fluid particle i of the primitive at fractional primitive frame s (Eq. 10's P_f);
/// past the last frame, the last frame's.
void primitivePosition(const PrimitiveView& p, std::uint32_t i, double s, float out[3]);

/// The primitive's drift: the mean displacement per frame, over its last kDriftFrames frames
/// (fewer if it is shorter), of the particles present at both ends; zero for one frame.
void primitiveDrift(const PrimitiveView& p, float out[3]);

/// How far a copy at primitive frame s has moved as a whole (in primitive metres): past the
/// last frame with PastLastFrame::Drift, drift tau (1 - exp(-(s - last) / tau)) with tau =
/// kDriftDecayFrames; else zero.
void copyShift(const PrimitiveView& p, const MappingSettings& s, const float drift[3], double time,
               float out[3]);

/// Origins P_s[L, j](t) of every source at frame t (Eq. 12), 3 floats each; zero for sources
/// that start after t.
std::vector<float> sourceOrigins(const SourceTable& table, int frame, const CondensationView& c,
                                 const PrimitiveLibrary& lib, const MappingSettings& s);

/// Velocities (m/s, 3 floats each) of every source's copy at frame t: copyOrigin's time
/// derivative; zero for sources that start after t. A level 1 copy moves with its
/// condensation particle (vx, vy, and vz unless it stands on the condensation level; a laid
/// Trail copy stands still), a deeper one with its parent particle (particleVelocity); past
/// the primitive's last frame the drift adds R drift exp(-(s - last) / tau) A / ds.
std::vector<float> copyVelocities(const SourceTable& table, int frame, const CondensationView& c,
                                  const PrimitiveLibrary& lib, const MappingSettings& s);

/// Velocity (m/s) of fluid id i of src's copy, whose copy moves at copyVelocity, at frame t:
/// Eq. 10 differentiated, copyVelocity + R (A / ds) (P_f(floor s + 1) - P_f(floor s)), as P_f
/// is linear between primitive frames; no change of shape past the last frame.
void particleVelocity(const Source& src, const float* copyVelocity, std::uint32_t i, int frame,
                      const PrimitiveView& p, const MappingSettings& s, float out[3]);

/// Per source, the first stable id of its copy's particles: the prefix sums of each copy's
/// largest particle count over all primitive frames, so particle q of source j's copy has id
/// base[j] + q on every frame (the table only appends). Throws std::invalid_argument when the
/// ids would not fit in 32 bits.
std::vector<std::uint64_t> particleIdBases(const SourceTable& table, const PrimitiveLibrary& lib,
                                           const MappingSettings& s);

/// N_c[L](t) for L = 1..maxLevel (Eq. 13): index L-1.
std::vector<std::uint64_t> cloudCounts(const SourceTable& table, int frame,
                                       const PrimitiveLibrary& lib, const MappingSettings& s);

/// One frame of pseudocode lines 15-28: selects the new sources of every active level at
/// frame t (Eq. 12, 14-16) and updates L_max. `firstCondensation` is t_s[1] from the
/// Condensation node (-1 if none yet). Returns the table at frame t.
SourceTable stepSources(const SourceTable& previous, int frame, int firstCondensation,
                        const CondensationView& c, const MapView& map, const PrimitiveLibrary& lib,
                        const MappingSettings& s);

/// A heap array of a trivial type whose elements are left uninitialised on allocation: a
/// frame-sized output is first touched by the parallel writers that fill it, not zero-filled
/// on one thread first (what std::vector::resize does; for a 4.6 M-particle frame that
/// zeroing and its page faults cost more than generating the particles). Arrays of
/// kHugePageAdviceBytes or more are advised onto huge pages. Move-only; reads like a const
/// std::vector (data, size, begin/end, []) and converts to one by copying.
template <class T>
class UninitArray {
    static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_default_constructible_v<T>,
                  "UninitArray holds plain values");

public:
    UninitArray() = default;
    explicit UninitArray(std::size_t n) : mData(n == 0 ? nullptr : new T[n]), mSize(n)
    {
        if (n * sizeof(T) >= util::kHugePageAdviceBytes)
            util::adviseHugePages(mData.get(), n * sizeof(T));
    }
    explicit UninitArray(const std::vector<T>& v) : UninitArray(v.size())
    {
        std::copy(v.begin(), v.end(), data());
    }

    T* data() { return mData.get(); }
    const T* data() const { return mData.get(); }
    std::size_t size() const { return mSize; }
    bool empty() const { return mSize == 0; }
    T* begin() { return data(); }
    T* end() { return data() + mSize; }
    const T* begin() const { return data(); }
    const T* end() const { return data() + mSize; }
    T& operator[](std::size_t i) { return mData[i]; }
    const T& operator[](std::size_t i) const { return mData[i]; }
    operator std::vector<T>() const { return std::vector<T>(begin(), end()); }  // NOLINT: a copy
    /// Keeps the first n elements (n <= size); the memory stays allocated.
    void shrink(std::size_t n) { mSize = std::min(n, mSize); }

private:
    std::unique_ptr<T[]> mData;
    std::size_t mSize = 0;
};

/// Particles a chunk of forEachCloudChunk by default: 48 KB of positions, cache-resident.
inline constexpr std::uint64_t kCloudChunkParticles = 4096;

/// One chunk of a frame's cloud particles: particles [first, first + count) in table order
/// (source by source, each source's fluid particles by id). The pointers are valid only during
/// the call that hands the chunk over.
struct CloudChunk {
    std::uint64_t first = 0;
    std::uint64_t count = 0;
    const float* positions = nullptr;        ///< 3 count floats: x, y, z in metres (Eq. 10)
    const std::uint8_t* levels = nullptr;    ///< count levels L; nullptr unless requested
    const std::uint32_t* sources = nullptr;  ///< count source indices j; nullptr unless requested
    /// The frame's copy origins (as CloudParticleArrays::copyOrigins: 3 floats for each of
    /// copyCount sources), the same for every chunk; what a consumer of sources needs to
    /// place a particle in its copy.
    const float* copyOrigins = nullptr;
    std::uint64_t copyCount = 0;
    /// 3 count floats, m/s: each particle's velocity, Eq. 10 differentiated in time (see
    /// particleVelocities); nullptr unless requested.
    const float* velocities = nullptr;
    /// count stable ids: the same particle has the same id on every frame (particleIdBases);
    /// nullptr unless requested.
    const std::uint32_t* ids = nullptr;
};

struct CloudChunkOptions {
    std::uint64_t chunkParticles = kCloudChunkParticles;  ///< particles a chunk (> 0)
    bool levels = false;                                  ///< also fill CloudChunk::levels
    bool sources = false;                                 ///< also fill CloudChunk::sources
    bool velocities = false;  ///< also fill CloudChunk::velocities (per-thread buffers only)
    bool ids = false;         ///< also fill CloudChunk::ids (per-thread buffers only)
    /// Where chunks are written. All null (the default): a reused per-thread buffer of one
    /// chunk, so nothing frame-sized exists. Otherwise frame arrays of the frame's particle
    /// count (positionsOut 3 floats a particle; levelsOut / sourcesOut required when levels /
    /// sources are requested): chunk [first, first + count) is written at index first.
    float* positionsOut = nullptr;
    std::uint8_t* levelsOut = nullptr;
    std::uint32_t* sourcesOut = nullptr;
    std::function<void()> checkCancelled;  ///< called before each chunk; may throw to stop
};

/// Generates the cloud particles of frame t (Eq. 10-12) chunk by chunk, in parallel (TBB),
/// and hands each chunk to consume (may be empty). Chunk k holds particles
/// [k chunkParticles, min((k + 1) chunkParticles, N)) of the frame: the boundaries and every
/// value depend only on the inputs, never on the thread count, and the chunks concatenated
/// are exactly generateCloudParticles' arrays, bit for bit. consume is called once per chunk,
/// concurrently from several threads and in no particular order, so it must be thread-safe
/// (a consumer that writes chunk k to its own slot, or accumulates per thread, is
/// deterministic). Per frame this keeps only the sources' origins and prefix sums
/// (20 bytes a source) and one chunk buffer per thread. Returns N, the frame's particle count.
std::uint64_t forEachCloudChunk(const SourceTable& table, int frame, const CondensationView& c,
                                const PrimitiveLibrary& lib, const MappingSettings& s,
                                const std::function<void(const CloudChunk&)>& consume,
                                const CloudChunkOptions& options = {});

/// Cloud particles of frame t (Eq. 10), in table order, parallel and deterministic: the
/// chunks of forEachCloudChunk written straight into fresh, uninitialised frame arrays
/// (17 bytes a particle), and the copies' origins (12 bytes a source).
struct CloudParticleArrays {
    UninitArray<float> positions;        ///< x, y, z per particle
    UninitArray<std::uint8_t> levels;    ///< level L per particle
    UninitArray<std::uint32_t> sources;  ///< source index j per particle
    /// Per source j, 3 floats: where its copy stands (its origin, Eq. 12, plus its drift past
    /// the primitive's end), so particle i of the copy is copyOrigins[j] + R P_f(i) (Eq. 10);
    /// zero for sources not started. What detail evaluated in copy coordinates needs.
    UninitArray<float> copyOrigins;
};
CloudParticleArrays generateCloudParticles(const SourceTable& table, int frame,
                                           const CondensationView& c, const PrimitiveLibrary& lib,
                                           const MappingSettings& s,
                                           const std::function<void()>& checkCancelled = {});

}  // namespace cg::algo
