#include "algo/volume/CopyTerritory.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <utility>

#include <tbb/enumerable_thread_specific.h>

#include "algo/CounterRandom.h"
#include "algo/volume/CoordKey.h"

namespace cg::algo {

namespace {

int cellOf(double x, double cellSize) { return static_cast<int>(std::floor(x / cellSize)); }

std::uint64_t keyOf(int i, int j, int k)
{
    if (!coordKeyable(i) || !coordKeyable(j) || !coordKeyable(k))
        throw std::invalid_argument("copy territory: a particle lies beyond 2^20 cells");
    return packCoordKey(i, j, k);
}

/// A (cell key, copy) pair.
struct CellCopy {
    std::uint64_t cell;
    std::uint32_t copy;
    bool operator==(const CellCopy& o) const { return cell == o.cell && copy == o.copy; }
    bool operator<(const CellCopy& o) const
    {
        return cell != o.cell ? cell < o.cell : copy < o.copy;
    }
};

struct CellCopyHash {
    std::size_t operator()(const CellCopy& c) const
    {
        return static_cast<std::size_t>(mix64(c.cell * 0x9e3779b97f4a7c15ull ^ c.copy));
    }
};

/// One thread's particle counts per (cell, copy), and the pair it counted last: a copy's
/// particles come in runs, mostly in one cell.
struct LocalCounts {
    std::unordered_map<CellCopy, std::uint64_t, CellCopyHash> counts;
    CellCopy last{~std::uint64_t(0), 0};
    std::uint64_t* lastCount = nullptr;
};

}  // namespace

struct CopyTerritory::Accumulator {
    tbb::enumerable_thread_specific<LocalCounts> locals;
    std::mutex originsLock;
    std::vector<float> origins;
};

CopyTerritory::CopyTerritory(double cellSize)
    : mCellSize(cellSize), mAccumulator(std::make_unique<Accumulator>())
{
    if (!(cellSize > 0.0) || !std::isfinite(cellSize))
        throw std::invalid_argument("copy territory: the cell size must be > 0");
}

CopyTerritory::~CopyTerritory() = default;
CopyTerritory::CopyTerritory(CopyTerritory&&) noexcept = default;
CopyTerritory& CopyTerritory::operator=(CopyTerritory&&) noexcept = default;

void CopyTerritory::add(const float* xyz, const std::uint32_t* sources, std::size_t count,
                        const float* copyOrigins, std::size_t copyCount)
{
    {
        // Every chunk of a frame carries the same origins: the first copy kept serves all.
        const std::lock_guard<std::mutex> lock(mAccumulator->originsLock);
        if (mAccumulator->origins.empty() && copyCount > 0)
            mAccumulator->origins.assign(copyOrigins, copyOrigins + 3 * copyCount);
    }
    LocalCounts& local = mAccumulator->locals.local();
    for (std::size_t i = 0; i < count; ++i) {
        if (sources[i] >= copyCount)
            throw std::invalid_argument("copy territory: a particle's copy has no origin");
        const CellCopy at{keyOf(cellOf(xyz[3 * i], mCellSize), cellOf(xyz[3 * i + 1], mCellSize),
                                cellOf(xyz[3 * i + 2], mCellSize)),
                          sources[i]};
        if (!(local.lastCount && at == local.last)) {
            local.last = at;
            local.lastCount = &local.counts[at];  // unordered_map values never move
        }
        ++*local.lastCount;
    }
}

void CopyTerritory::finish()
{
    if (!mAccumulator) return;
    std::vector<std::pair<CellCopy, std::uint64_t>> all;
    for (LocalCounts& local : mAccumulator->locals)
        all.insert(all.end(), local.counts.begin(), local.counts.end());
    std::sort(all.begin(), all.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    // Sum each pair over the threads, then keep each cell's largest (the lower copy on ties).
    std::uint64_t bestCount = 0;
    for (std::size_t i = 0; i < all.size();) {
        const CellCopy pair = all[i].first;
        std::uint64_t n = 0;
        for (; i < all.size() && all[i].first == pair; ++i) n += all[i].second;
        const auto owner = mOwner.find(pair.cell);
        if (owner == mOwner.end()) {
            mOwner.emplace(pair.cell, pair.copy);
            bestCount = n;
        } else if (n > bestCount) {
            owner->second = pair.copy;
            bestCount = n;
        }
    }
    mOrigins = std::move(mAccumulator->origins);
    mAccumulator.reset();
}

std::int64_t CopyTerritory::ownerOfCell(int i, int j, int k) const
{
    if (!coordKeyable(i) || !coordKeyable(j) || !coordKeyable(k)) return -1;
    const auto it = mOwner.find(packCoordKey(i, j, k));
    return it == mOwner.end() ? -1 : static_cast<std::int64_t>(it->second);
}

std::int64_t CopyTerritory::owner(const double x[3]) const
{
    return ownerOfCell(cellOf(x[0], mCellSize), cellOf(x[1], mCellSize), cellOf(x[2], mCellSize));
}

std::vector<std::uint32_t> CopyTerritory::ownersIn(const double lo[3], const double hi[3]) const
{
    std::vector<std::uint32_t> owners;
    for (int i = cellOf(lo[0], mCellSize); i <= cellOf(hi[0], mCellSize); ++i)
        for (int j = cellOf(lo[1], mCellSize); j <= cellOf(hi[1], mCellSize); ++j)
            for (int k = cellOf(lo[2], mCellSize); k <= cellOf(hi[2], mCellSize); ++k) {
                const std::int64_t o = ownerOfCell(i, j, k);
                if (o >= 0) owners.push_back(static_cast<std::uint32_t>(o));
            }
    std::sort(owners.begin(), owners.end());
    owners.erase(std::unique(owners.begin(), owners.end()), owners.end());
    return owners;
}

void CopyTerritory::origin(std::uint32_t j, double out[3]) const
{
    for (int a = 0; a < 3; ++a) out[a] = mOrigins[3 * static_cast<std::size_t>(j) + a];
}

}  // namespace cg::algo
