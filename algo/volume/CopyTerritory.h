#pragma once
/// Which copy owns each region of a cloud: cubic cells binned from the particles, each owned
/// by the copy (Eq. 12's source j) with the most particles in it (the lower j on a tie), with
/// the copies' origins (Eq. 12's origin plus the copy's drift). Detail that must ride with
/// the copies places each feature in its own copy's coordinates and keeps it only inside
/// that copy's territory: no feature is ever evaluated in a blend of two copies'
/// coordinates, which squashes it where copies overlap.
///
/// Deterministic for any thread count and any order of the particles: the counts are
/// integers. Particles may be added in chunks from several threads. No engine includes.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

namespace cg::algo {

class CopyTerritory {
public:
    /// cellSize > 0, metres.
    explicit CopyTerritory(double cellSize);
    ~CopyTerritory();
    CopyTerritory(CopyTerritory&&) noexcept;
    CopyTerritory& operator=(CopyTerritory&&) noexcept;

    /// Bins `count` particles at `xyz` (metres) of copies sources[i] < copyCount, whose
    /// origins are copyOrigins[3 j ...] (the same array for every call of a frame). Safe from
    /// several threads at once, before finish. Throws std::invalid_argument for a source
    /// without an origin or a particle beyond 2^20 cells.
    void add(const float* xyz, const std::uint32_t* sources, std::size_t count,
             const float* copyOrigins, std::size_t copyCount);
    /// Merges what the threads added; the territory can be read from then on.
    void finish();

    /// The copy owning the cell around x, or -1 where no particle is.
    std::int64_t owner(const double x[3]) const;
    /// The owners of the cells that meet the box [lo, hi], each once, in increasing order.
    std::vector<std::uint32_t> ownersIn(const double lo[3], const double hi[3]) const;
    /// The copy owning cell (i, j, k), the cell [i, i + 1) x cellSize along x and so on; -1
    /// where no particle is.
    std::int64_t ownerOfCell(int i, int j, int k) const;
    double cellSize() const { return mCellSize; }
    /// Copy j's origin, metres.
    void origin(std::uint32_t j, double out[3]) const;

    bool empty() const { return mOwner.empty(); }

private:
    struct Accumulator;

    double mCellSize;
    std::unique_ptr<Accumulator> mAccumulator;
    std::unordered_map<std::uint64_t, std::uint32_t> mOwner;  ///< cell key -> copy
    std::vector<float> mOrigins;                              ///< 3 per copy
};

}  // namespace cg::algo
