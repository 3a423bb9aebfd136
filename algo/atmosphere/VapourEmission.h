#pragma once
/// Initial arrangement of water vapour particles over the ground (paper Sec. 5.1, Eq. 3-5).
///
/// Each map cell (ix, iy) with density fNoise(ix, iy) in [0, 1] emits
///   W_p   = W_p_min + (W_p_max - W_p_min) * fNoise                                   (Eq. 3)
/// particles, rounded half up: count = floor(W_p + 0.5), so 2.5 -> 3, 2.49 -> 2, and a
/// W_p <= -0.5 gives 0. Every particle of the cell starts at
///   P_vz  = P_vz_min + (P_vz_max - P_vz_min) * fNoise                                (Eq. 4)
///   T_v   = T_v_max - (T_v_max - T_v_min) * (P_vz - P_vz_min) / (P_vz_max - P_vz_min) (Eq. 5)
/// with T_v = T_v_max when P_vz_max == P_vz_min (Eq. 5 is 0/0 there; every particle is at the
/// one allowed height, which we treat as the warm ground end of the range), at rest (U_vz = 0)
/// and at a horizontal position uniform inside the cell.
///
/// Determinism: cells are taken in row-major order (iy outer, ix inner) and particles get
/// ids 0..N-1 in that order. x, y come from a counter-based generator keyed by (seed, cell,
/// particle index within the cell), so the output is identical for any thread count.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace cg::algo {

struct VapourEmissionSettings {
    double minParticlesPerCell = 0.0;  ///< W_p_min of Eq. 3 (particles)
    double maxParticlesPerCell = 6.0;  ///< W_p_max of Eq. 3 (particles)
    double minHeight = 0.0;            ///< P_vz_min of Eq. 4 (m)
    double maxHeight = 100.0;          ///< P_vz_max of Eq. 4 (m)
    double minTemperature = 29.0;      ///< T_v_min of Eq. 5 (degrees Celsius)
    double maxTemperature = 30.0;      ///< T_v_max of Eq. 5 (degrees Celsius)
    std::uint64_t seed = 0;            ///< keys the horizontal positions
};

/// The emitted particles as structure-of-arrays; all arrays have size().
struct VapourEmission {
    std::vector<std::uint32_t> id;        ///< 0..N-1 in emission order
    std::vector<std::uint32_t> homeCell;  ///< iy * nx + ix of the emitting cell
    std::vector<float> x;                 ///< metres, in [ix, ix+1) * cellSize
    std::vector<float> y;                 ///< metres, in [iy, iy+1) * cellSize
    std::vector<float> z;                 ///< P_vz(t0) of Eq. 4, metres
    std::vector<float> vz;                ///< U_vz(t0) = 0, m/s
    std::vector<float> temperature;       ///< T_v(t0) of Eq. 5, degrees Celsius

    std::size_t size() const { return id.size(); }
};

/// Bytes one emitted particle may occupy: id, home cell and eight floats (x, y, z, U_vz, T_v,
/// and as statics its start height, dew-point offset and release time).
constexpr std::uint64_t kVapourParticleBytes = 2 * sizeof(std::uint32_t) + 8 * sizeof(float);

/// Ours: particle `id` leaves its start at duration * u, u uniform in [0, 1) keyed by (seed,
/// id), so a source keeps feeding its tower for `duration` seconds.
float releaseTime(std::uint64_t seed, std::uint32_t id, double duration);

/// Particles of one cell of density `density` (Eq. 3 rounded half up, never negative,
/// capped at 2^53). `density` must be finite.
std::uint64_t cellParticleCount(double density, const VapourEmissionSettings& settings);

/// Total particles over `values` (the sum of cellParticleCount), saturating at
/// UINT64_MAX, so callers can check it against a limit before anything is allocated.
/// Non-finite values count as 0 here; emitVapour() refuses them.
std::uint64_t emissionCount(const std::vector<float>& values,
                            const VapourEmissionSettings& settings);

/// Emits the particles of an nx x ny map (row-major values, cells of cellSize metres).
/// Throws std::invalid_argument when nx, ny or cellSize is not positive, values.size() is not
/// nx * ny, a value is outside [0, 1] or not finite (naming the cell), or a cell is too small
/// for float positions to fall strictly inside it; std::length_error when the total exceeds
/// 2^32 - 1 (ids are 32-bit). The count is taken first, so the arrays are allocated once.
/// `poll`, when set, is called now and then from worker threads and may throw to cancel.
VapourEmission emitVapour(int nx, int ny, double cellSize, const std::vector<float>& values,
                          const VapourEmissionSettings& settings,
                          const std::function<void()>& poll = {});

}  // namespace cg::algo
