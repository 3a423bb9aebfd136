#pragma once
/// Where each region of a cloud has its local origin: the origin of the copy (Eq. 10's
/// P_s[L, j](t) plus the copy's drift) that its particles belong to, as a smooth field, so
/// that noise evaluated at x - origin(x) moves with the copies instead of swimming through
/// them.
///
/// Particles are binned into cubic cells of edge 2R (R the splat radius); a cell keeps the
/// sum of its particles' copy origins and their count. origin(x) interpolates the sums and
/// the counts trilinearly between the eight cell centres around x and divides: inside one
/// copy every particle has the same origin, so the field is that origin exactly (to double
/// rounding), wherever the copy has moved; where copies meet it is their particle-weighted
/// mean. With cells of 2R, a point within R of any particle always has that particle's cell
/// among its eight corners, so every voxel a splat reaches has an origin.
///
/// Deterministic for any thread count and any order of the particles: the sums are integers
/// (origins in units of 2^-10 m, so a copy origin must lie within 1,000 km), which add
/// associatively. So particles can be added in chunks from several threads as they stream
/// from the mapper. The same cells average any vector a particle carries instead of its
/// copy's origin (addVectors: the velocity field). No engine includes.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

namespace cg::algo {

class CopyOriginField {
public:
    /// Bins `count` particles at `xyz` (metres), particle i moving with the copy origin
    /// copyOrigins[3 sources[i] ...]. Every sources[i] must be below `copyCount`
    /// (std::invalid_argument otherwise). cellSize > 0, in metres.
    CopyOriginField(const float* xyz, const std::uint32_t* sources, std::size_t count,
                    const float* copyOrigins, std::size_t copyCount, double cellSize);

    /// An empty field to `add` particles to, then `finish` before reading it.
    explicit CopyOriginField(double cellSize);
    ~CopyOriginField();
    CopyOriginField(CopyOriginField&&) noexcept;
    CopyOriginField& operator=(CopyOriginField&&) noexcept;

    /// Bins particles as the first constructor does. Safe to call from several threads at
    /// once, before finish. Throws std::invalid_argument for a source without a copy origin,
    /// an origin that is not finite or lies beyond 1,000 km, a particle beyond 2^20 cells.
    void add(const float* xyz, const std::uint32_t* sources, std::size_t count,
             const float* copyOrigins, std::size_t copyCount);
    /// Bins particles each with a vector of its own (3 floats a particle, |v| < 1,000 km in
    /// the field's units): the field is then their mean, as with copy origins. Safe to call
    /// from several threads at once, before finish; not to be mixed with `add`.
    void addVectors(const float* xyz, const float* vectors, std::size_t count);
    /// Merges what the threads added; the field can be read from then on.
    void finish();

    /// A cell: the sum of its particles' copy origins and their count.
    struct Cell {
        double sum[3] = {0.0, 0.0, 0.0};
        double count = 0.0;
    };

    /// The cells whose centres surround the box [lo, hi] (metres) for interpolation, copied
    /// into a dense block (empty cells are zero): what origin() reads for every point in
    /// the box, fetched once instead of eight lookups a point.
    class Block {
    public:
        /// Where a coordinate on one axis lies among the block's cell centres: the lower
        /// corner cell and the upper one's weight; base < 0 outside the block's box.
        struct AxisPlace {
            int base = -1;
            double t = 0.0;
        };
        AxisPlace place(int axis, double x) const;

        /// The interpolated origin at x, inside the block's box; false where no particle's
        /// cell is among the eight corners (x farther than R from every particle).
        bool origin(const double x[3], double out[3]) const;
        /// The same from x's places on the three axes, which a caller on a lattice (a
        /// leaf's 8 coordinates per axis) finds once per coordinate instead of per point.
        bool origin(const AxisPlace (&at)[3], double out[3]) const;

    private:
        friend class CopyOriginField;
        double mCellSize = 1.0;
        int mLo[3] = {0, 0, 0};   ///< first cell of the block per axis
        int mDim[3] = {0, 0, 0};  ///< cells per axis
        std::vector<Cell> mCells;
    };
    Block block(const double lo[3], const double hi[3]) const;

    std::size_t cellCount() const { return mIndex.size(); }

private:
    struct KeyHash {
        std::size_t operator()(std::uint64_t k) const;
    };
    static std::uint64_t key(int i, int j, int k);

    struct Accumulator;  ///< the threads' integer sums while particles are added

    double mCellSize;
    std::unique_ptr<Accumulator> mAccumulator;
    std::unordered_map<std::uint64_t, std::uint32_t, KeyHash> mIndex;  ///< cell -> mCells index
    std::vector<Cell> mCells;
};

}  // namespace cg::algo
