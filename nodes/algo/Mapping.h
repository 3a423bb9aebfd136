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
/// interpolated linearly between frames floor s and floor s + 1; past the primitive's last
/// frame, the last frame holds.

#include <cstdint>
#include <functional>
#include <vector>

namespace cg::algo {

/// One source record j: what Eq. 10-12 and 16 need to place its cluster at any frame.
struct Source {
    std::uint8_t level = 1;       ///< L
    std::uint32_t parent = 0;     ///< L = 1: condensation particle index; L >= 2: source index j'
    std::uint32_t parentFluid = 0;///< L >= 2: fluid particle id i' of the parent cluster
    std::int32_t startFrame = 0;  ///< t0[L, j]
    float speed = 1.0f;           ///< A[L, j] = 1 + A0 fNoise (Eq. 16)
    float scale = 0.0f;           ///< R[L, j] = R0 fNoise (Eq. 16)
};

/// The mapper's whole state at one frame.
struct SourceTable {
    std::vector<Source> sources;            ///< in order of selection; parents precede children
    std::int32_t topLevel = 1;              ///< L_max so far (pseudocode lines 7, 26-27)
    std::vector<std::int32_t> levelStart;   ///< t_s[L] per level (index L-1); -1 while unknown
    /// Condensation particles already selected (index -> 1): each is a source at most once.
    std::vector<std::uint8_t> condensationTaken;
    /// Cloud particles already selected, as (j' << 32 | i'), sorted: each at most once.
    std::vector<std::uint64_t> cloudTaken;
};

/// A read-only view of the primitive set: N_f(s) and frame positions (xyz floats).
struct PrimitiveView {
    const std::uint32_t* counts = nullptr;
    const float* const* frames = nullptr;  ///< frames[s] -> N_f(s) xyz triples
    int frameCount = 0;
    double frameTime = 1.0;                ///< ds, seconds
};

/// A read-only view of the condensation particles at frame t.
struct CondensationView {
    const float* x = nullptr;
    const float* y = nullptr;
    const float* z = nullptr;
    const std::int32_t* condensedFrame = nullptr;  ///< -1 while still vapour
    std::size_t count = 0;
};

/// A read-only view of the density map fNoise.
struct MapView {
    const float* values = nullptr;
    int nx = 0;
    int ny = 0;
    double cellSize = 1.0;
    float at(double x, double y) const;  ///< fNoise of the cell under (x, y), clamped to the map
};

struct MappingSettings {
    int maxLevel = 5;                           ///< cap on L_max
    std::vector<double> selectionRatio{0.2};    ///< M[L]; the last value repeats for higher L
    int firstStart = -1;                        ///< t_s[1]; -1: the first condensation frame
    int levelDelay = 50;                        ///< chi: t_s[L] = t_s[L-1] + chi
    std::vector<int> windowLength{100, 60};     ///< t_e[L] - t_s[L]; the last value repeats
    double scaleCoefficient = 1.5;              ///< R0 of Eq. 16
    double speedCoefficient = 2.0;              ///< A0 of Eq. 16
    double metresPerPrimitiveMetre = 1.0;       ///< global scale of every cluster (ours)
    double timeStep = 1.0;                      ///< dt of the stochastic simulation, seconds
    std::uint64_t seed = 0;
    std::uint64_t maxSources = 1u << 24;        ///< selection stops here (a memory guard)
};

double selectionRatio(const MappingSettings& s, int level);
int windowLength(const MappingSettings& s, int level);

/// Primitive frame s of a source at stochastic frame t (Eq. 11).
double primitiveTime(const Source& src, int frame, const MappingSettings& s, const PrimitiveView& p);
/// N_f(s) for a source at frame t (0 before its start).
std::uint32_t clusterSize(const Source& src, int frame, const MappingSettings& s, const PrimitiveView& p);
/// Position of fluid particle i of the primitive at fractional primitive frame s (Eq. 10's P_f).
void primitivePosition(const PrimitiveView& p, std::uint32_t i, double s, float out[3]);

/// Origins P_s[L, j](t) of every source at frame t (Eq. 12), 3 floats each; zero for sources
/// that start after t.
std::vector<float> sourceOrigins(const SourceTable& table, int frame, const CondensationView& c,
                                 const PrimitiveView& p, const MappingSettings& s);

/// N_c[L](t) for L = 1..maxLevel (Eq. 13): index L-1.
std::vector<std::uint64_t> cloudCounts(const SourceTable& table, int frame, const PrimitiveView& p,
                                       const MappingSettings& s);

/// One frame of pseudocode lines 15-28: selects the new sources of every active level at
/// frame t (Eq. 12, 14-16) and updates L_max. `firstCondensation` is t_s[1] from the
/// Condensation node (-1 if none yet). Returns the table at frame t.
SourceTable stepSources(const SourceTable& previous, int frame, int firstCondensation,
                        const CondensationView& c, const MapView& map, const PrimitiveView& p,
                        const MappingSettings& s);

/// Cloud particles of frame t (Eq. 10), in table order, parallel and deterministic.
struct CloudParticleArrays {
    std::vector<float> positions;
    std::vector<std::uint8_t> levels;
    std::vector<std::uint32_t> sources;
};
CloudParticleArrays generateCloudParticles(const SourceTable& table, int frame,
                                           const CondensationView& c, const PrimitiveView& p,
                                           const MappingSettings& s,
                                           const std::function<void()>& checkCancelled = {});

}  // namespace cg::algo
