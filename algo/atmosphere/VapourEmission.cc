#include "algo/atmosphere/VapourEmission.h"

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "algo/CounterRandom.h"

namespace cg::algo {

float releaseTime(std::uint64_t seed, std::uint32_t id, double duration)
{
    constexpr std::uint64_t kReleaseStream = 0x72656c65617365ull;  // "release": above any cell
    return static_cast<float>(duration * counterUniform(seed, kReleaseStream, id));
}

namespace {

constexpr double kMaxCellCount = 9007199254740992.0;  // 2^53: every count below is exact

std::string cellName(std::size_t cell, int nx)
{
    const auto n = static_cast<std::size_t>(nx);
    return "cell (" + std::to_string(cell % n) + ", " + std::to_string(cell / n) + ")";
}

/// A float coordinate uniform in [i, i+1) * cellSize that stays below the upper edge after
/// rounding to float (and not below the lower one), so a particle never leaks into the next
/// cell.
float insideCell(int i, double cellSize, double u)
{
    const double lo = i * cellSize;
    const double hi = (i + 1) * cellSize;
    float v = static_cast<float>(lo + u * cellSize);
    constexpr float kInf = std::numeric_limits<float>::infinity();
    while (static_cast<double>(v) >= hi) v = std::nextafter(v, -kInf);
    while (static_cast<double>(v) < lo) v = std::nextafter(v, kInf);
    if (static_cast<double>(v) >= hi)
        throw std::invalid_argument("cell size " + std::to_string(cellSize) +
                                    " m is too small for float positions at " + std::to_string(lo) +
                                    " m");
    return v;
}

}  // namespace

std::uint64_t cellParticleCount(double density, const VapourEmissionSettings& s)
{
    const double w =
        s.minParticlesPerCell + (s.maxParticlesPerCell - s.minParticlesPerCell) * density;
    // Round half up without the double rounding of floor(w + 0.5): w - floor(w) is exact.
    double r = std::floor(w);
    if (w - r >= 0.5) r += 1.0;
    if (!(r > 0.0)) return 0;  // also NaN
    if (r >= kMaxCellCount) return static_cast<std::uint64_t>(kMaxCellCount);
    return static_cast<std::uint64_t>(r);
}

std::uint64_t emissionCount(const std::vector<float>& values, const VapourEmissionSettings& s)
{
    std::uint64_t total = 0;
    for (float v : values) {
        if (!std::isfinite(v)) continue;
        const std::uint64_t n = cellParticleCount(v, s);
        if (n > std::numeric_limits<std::uint64_t>::max() - total)
            return std::numeric_limits<std::uint64_t>::max();
        total += n;
    }
    return total;
}

VapourEmission emitVapour(int nx, int ny, double cellSize, const std::vector<float>& values,
                          const VapourEmissionSettings& s, const std::function<void()>& poll)
{
    if (nx <= 0 || ny <= 0 || !(cellSize > 0.0) || !std::isfinite(cellSize))
        throw std::invalid_argument("emitVapour: the map needs nx, ny and cellSize > 0");
    const std::size_t cells = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
    if (values.size() != cells)
        throw std::invalid_argument("emitVapour: the map has " + std::to_string(values.size()) +
                                    " values for " + std::to_string(cells) + " cells");
    if (cells - 1 > std::numeric_limits<std::uint32_t>::max())
        throw std::length_error("emitVapour: more cells than 32-bit home cell indices can name");
    for (std::size_t c = 0; c < cells; ++c) {
        const float v = values[c];
        if (!(v >= 0.0f && v <= 1.0f))  // also NaN
            throw std::invalid_argument("density " + std::to_string(v) + " at " + cellName(c, nx) +
                                        " is outside [0, 1] (Eq. 3)");
    }

    // Count first, so every array is allocated once at its final size.
    std::vector<std::uint64_t> first(cells + 1, 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells), [&](const auto& r) {
        for (std::size_t c = r.begin(); c != r.end(); ++c)
            first[c + 1] = cellParticleCount(values[c], s);
    });
    for (std::size_t c = 0; c < cells; ++c) {
        if (first[c + 1] > std::numeric_limits<std::uint32_t>::max() - first[c])
            throw std::length_error("emitVapour: more than 2^32 - 1 particles; ids are 32-bit");
        first[c + 1] += first[c];
    }
    const auto total = static_cast<std::size_t>(first[cells]);

    VapourEmission out;
    out.id.resize(total);
    out.homeCell.resize(total);
    out.x.resize(total);
    out.y.resize(total);
    out.z.resize(total);
    out.vz.assign(total, 0.0f);  // the particles start at rest
    out.temperature.resize(total);

    const double heightSpan = s.maxHeight - s.minHeight;
    const double temperatureSpan = s.maxTemperature - s.minTemperature;
    // Each cell writes only its own slice [first[c], first[c+1]) from counters that do not
    // depend on the schedule, so the result is the same for any thread count.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells), [&](const auto& r) {
        if (poll) poll();
        for (std::size_t c = r.begin(); c != r.end(); ++c) {
            const std::size_t begin = static_cast<std::size_t>(first[c]);
            const std::size_t end = static_cast<std::size_t>(first[c + 1]);
            if (begin == end) continue;
            const int ix = static_cast<int>(c % static_cast<std::size_t>(nx));
            const int iy = static_cast<int>(c / static_cast<std::size_t>(nx));
            const double f = values[c];
            const double height = s.minHeight + heightSpan * f;  // Eq. 4
            // Eq. 5; with a single allowed height the ratio is 0/0 and T_v is T_v_max.
            const double temperature =
                heightSpan == 0.0
                    ? s.maxTemperature
                    : s.maxTemperature - temperatureSpan * (height - s.minHeight) / heightSpan;
            for (std::size_t i = begin; i < end; ++i) {
                const std::uint64_t k = i - begin;  // index within the cell
                out.id[i] = static_cast<std::uint32_t>(i);
                out.homeCell[i] = static_cast<std::uint32_t>(c);
                out.x[i] = insideCell(ix, cellSize, counterUniform(s.seed, c, 2 * k));
                out.y[i] = insideCell(iy, cellSize, counterUniform(s.seed, c, 2 * k + 1));
                out.z[i] = static_cast<float>(height);
                out.temperature[i] = static_cast<float>(temperature);
            }
        }
    });
    return out;
}

}  // namespace cg::algo
