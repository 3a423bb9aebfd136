#include "algo/volume/CopyOriginField.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "algo/CounterRandom.h"
#include "algo/volume/CoordKey.h"
#include "algo/volume/RecentLookup.h"
#include "util/CheckedSize.h"

namespace cg::algo {

namespace {

/// Particles per task when a whole array is added (the sums do not depend on it).
constexpr std::size_t kChunk = std::size_t(1) << 16;
/// Copy origins are summed in units of 2^-10 m: |origin| < 2^20 m keeps a term under 2^30
/// and the sum of up to 2^32 particles inside an int64.
constexpr double kOriginUnits = 1024.0;
constexpr double kMaxOrigin = 1048576.0;

int cellOf(double x, double cellSize) { return static_cast<int>(std::floor(x / cellSize)); }

}  // namespace

std::size_t CopyOriginField::KeyHash::operator()(std::uint64_t k) const
{
    return static_cast<std::size_t>(mix64(k));
}

std::uint64_t CopyOriginField::key(int i, int j, int k)
{
    if (!coordKeyable(i) || !coordKeyable(j) || !coordKeyable(k))
        throw std::invalid_argument("copy origin field: a particle lies beyond 2^20 cells");
    return packCoordKey(i, j, k);
}

namespace {

/// A cell's sums while particles are added: origins in units of 2^-10 m.
struct IntegerCell {
    std::int64_t sum[3] = {0, 0, 0};
    std::uint64_t count = 0;
};

}  // namespace

struct CopyOriginField::Accumulator {
    /// One thread's cells; the cells used lately are remembered (a copy's particles fall in a
    /// few dozen cells: the hash is mostly skipped).
    struct LocalCells {
        std::unordered_map<std::uint64_t, IntegerCell, KeyHash> cells;
        RecentLookup<IntegerCell, 9> recent;
    };
    tbb::enumerable_thread_specific<LocalCells> locals;
};

CopyOriginField::CopyOriginField(double cellSize)
    : mCellSize(cellSize), mAccumulator(std::make_unique<Accumulator>())
{
    if (!(cellSize > 0.0) || !std::isfinite(cellSize))
        throw std::invalid_argument("copy origin field: the cell size must be > 0");
}

CopyOriginField::CopyOriginField(const float* xyz, const std::uint32_t* sources, std::size_t count,
                                 const float* copyOrigins, std::size_t copyCount, double cellSize)
    : CopyOriginField(cellSize)
{
    tbb::parallel_for(std::size_t(0), (count + kChunk - 1) / kChunk, [&](std::size_t c) {
        const std::size_t first = c * kChunk;
        add(xyz + 3 * first, sources + first, std::min(kChunk, count - first), copyOrigins,
            copyCount);
    });
    finish();
}

CopyOriginField::~CopyOriginField() = default;
CopyOriginField::CopyOriginField(CopyOriginField&&) noexcept = default;
CopyOriginField& CopyOriginField::operator=(CopyOriginField&&) noexcept = default;

void CopyOriginField::add(const float* xyz, const std::uint32_t* sources, std::size_t count,
                          const float* copyOrigins, std::size_t copyCount)
{
    Accumulator::LocalCells& local = mAccumulator->locals.local();
    // Particles come in runs of one source: its origin is checked and rounded once a run.
    std::uint32_t lastSource = 0;
    std::int64_t origin[3] = {0, 0, 0};
    for (std::size_t i = 0; i < count; ++i) {
        const std::uint32_t s = sources[i];
        if (i == 0 || s != lastSource) {
            if (s >= copyCount)
                throw std::invalid_argument(
                    "copy origin field: a particle's source has no copy origin");
            for (int a = 0; a < 3; ++a) {
                const double o = copyOrigins[3 * static_cast<std::size_t>(s) + a];
                if (!(std::fabs(o) < kMaxOrigin))
                    throw std::invalid_argument(
                        "copy origin field: a copy origin is not finite or lies "
                        "beyond 1,000 km");
                origin[a] = std::llround(o * kOriginUnits);
            }
            lastSource = s;
        }
        const float* p = xyz + 3 * i;
        const std::uint64_t k =
            key(cellOf(p[0], mCellSize), cellOf(p[1], mCellSize), cellOf(p[2], mCellSize));
        // unordered_map nodes stay where they are: the remembered pointers stay valid.
        IntegerCell* cell = local.recent.get(k, [&] { return &local.cells[k]; });
        for (int a = 0; a < 3; ++a) cell->sum[a] += origin[a];
        ++cell->count;
    }
}

void CopyOriginField::addVectors(const float* xyz, const float* vectors, std::size_t count)
{
    Accumulator::LocalCells& local = mAccumulator->locals.local();
    for (std::size_t i = 0; i < count; ++i) {
        std::int64_t value[3];
        for (int a = 0; a < 3; ++a) {
            const double v = vectors[3 * i + a];
            if (!(std::fabs(v) < kMaxOrigin))
                throw std::invalid_argument(
                    "cell field: a particle's vector is not finite or beyond 1,000 km");
            value[a] = std::llround(v * kOriginUnits);
        }
        const float* p = xyz + 3 * i;
        const std::uint64_t k =
            key(cellOf(p[0], mCellSize), cellOf(p[1], mCellSize), cellOf(p[2], mCellSize));
        IntegerCell* cell = local.recent.get(k, [&] { return &local.cells[k]; });
        for (int a = 0; a < 3; ++a) cell->sum[a] += value[a];
        ++cell->count;
    }
}

void CopyOriginField::finish()
{
    std::unordered_map<std::uint64_t, IntegerCell, KeyHash> total;
    for (const Accumulator::LocalCells& local : mAccumulator->locals)
        for (const auto& [k, cell] : local.cells) {
            IntegerCell& t = total[k];
            for (int a = 0; a < 3; ++a) t.sum[a] += cell.sum[a];
            t.count += cell.count;
        }
    mAccumulator->locals.clear();  // the cells and the pointers remembered to them
    mIndex.reserve(total.size());
    mCells.reserve(total.size());
    for (const auto& [k, cell] : total) {
        mIndex.emplace(k, static_cast<std::uint32_t>(mCells.size()));
        Cell c;
        for (int a = 0; a < 3; ++a) c.sum[a] = static_cast<double>(cell.sum[a]) / kOriginUnits;
        c.count = static_cast<double>(cell.count);
        mCells.push_back(c);
    }
}

CopyOriginField::Block CopyOriginField::block(const double lo[3], const double hi[3]) const
{
    Block b;
    b.mCellSize = mCellSize;
    for (int a = 0; a < 3; ++a) {
        // The corners of x are the cells floor(x / C - 1/2) and the next.
        b.mLo[a] = static_cast<int>(std::floor(lo[a] / mCellSize - 0.5));
        b.mDim[a] = static_cast<int>(std::floor(hi[a] / mCellSize - 0.5)) + 2 - b.mLo[a];
    }
    const std::optional<std::uint64_t> cells =
        util::checkedProduct({b.mDim[0], b.mDim[1], b.mDim[2]});
    if (!cells) throw std::invalid_argument("copy origin field: the block has too many cells");
    b.mCells.resize(static_cast<std::size_t>(*cells));
    std::size_t n = 0;
    for (int i = 0; i < b.mDim[0]; ++i)
        for (int j = 0; j < b.mDim[1]; ++j)
            for (int k = 0; k < b.mDim[2]; ++k, ++n) {
                const int c[3] = {b.mLo[0] + i, b.mLo[1] + j, b.mLo[2] + k};
                if (!coordKeyable(c[0]) || !coordKeyable(c[1]) || !coordKeyable(c[2]))
                    continue;  // beyond every particle: empty
                const auto it = mIndex.find(key(c[0], c[1], c[2]));
                if (it != mIndex.end()) b.mCells[n] = mCells[it->second];
            }
    return b;
}

CopyOriginField::Block::AxisPlace CopyOriginField::Block::place(int axis, double x) const
{
    const double u = x / mCellSize - 0.5;
    const double f = std::floor(u);
    const int base = static_cast<int>(f) - mLo[axis];
    // A point outside the block's box has no corners here.
    if (base < 0 || base + 1 >= mDim[axis]) return {};
    return {base, u - f};
}

bool CopyOriginField::Block::origin(const double x[3], double out[3]) const
{
    const AxisPlace at[3] = {place(0, x[0]), place(1, x[1]), place(2, x[2])};
    return origin(at, out);
}

bool CopyOriginField::Block::origin(const AxisPlace (&at)[3], double out[3]) const
{
    if (at[0].base < 0 || at[1].base < 0 || at[2].base < 0) return false;
    const std::size_t strideY = static_cast<std::size_t>(mDim[2]);
    const std::size_t strideX = static_cast<std::size_t>(mDim[1]) * strideY;
    const std::size_t first = static_cast<std::size_t>(at[0].base) * strideX +
                              static_cast<std::size_t>(at[1].base) * strideY +
                              static_cast<std::size_t>(at[2].base);
    double sum[3] = {0.0, 0.0, 0.0}, count = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        const int bx = (corner >> 2) & 1, by = (corner >> 1) & 1, bz = corner & 1;
        const Cell& c = mCells[first + bx * strideX + by * strideY + static_cast<std::size_t>(bz)];
        if (c.count == 0.0) continue;
        // The weight multiplied in axis order from 1, as the sums have always been made.
        double w = 1.0;
        w *= bx ? at[0].t : 1.0 - at[0].t;
        w *= by ? at[1].t : 1.0 - at[1].t;
        w *= bz ? at[2].t : 1.0 - at[2].t;
        for (int a = 0; a < 3; ++a) sum[a] += w * c.sum[a];
        count += w * c.count;
    }
    if (!(count > 0.0)) return false;
    for (int a = 0; a < 3; ++a) out[a] = sum[a] / count;
    return true;
}

}  // namespace cg::algo
