#include "algo/volume/Voxelize.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

#include <openvdb/tools/Filter.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "algo/volume/GaussianSplat.h"
#include "algo/volume/LeafFromDense.h"
#include "util/HugePages.h"

namespace cg::algo {

namespace {

using LeafT = openvdb::FloatTree::LeafNodeType;
static_assert(LeafT::LOG2DIM == 3, "the bricks below hold whole 8^3-voxel leaves");
/// Particles are binned by brick, a cube of 4^3 leaves (32^3 voxels), and each brick is summed
/// in a dense accumulator that stays in the L2 cache. Bricks rather than leaves: a footprint
/// crosses fewer brick faces (fewer duplicate entries), and scattering entries into a few
/// hundred bricks stays in cache where scattering into thousands of leaves missed on every
/// store.
constexpr int kBrickLog2 = 5;
constexpr int kBrick = 1 << kBrickLog2;
constexpr int kBrickMax = kBrick - 1;  // last voxel of a brick along an axis, from its origin

/// Fixed work unit (particles or sort entries) so the partition never depends on the thread
/// count; only the brick sums need a fixed order, but fixed chunks keep every phase reproducible.
constexpr std::size_t kChunk = std::size_t(1) << 16;
/// Index coordinates are limited to +-2^20 voxels so three brick coordinates pack into 64 bits.
constexpr float kMaxIndex = 1048576.0f;

struct Kernel {
    float invVoxel;  ///< 1 / voxel size, 1/m
    float rv;        ///< kernel radius in voxels
    float rv2;       ///< rv^2
    float invRv2;    ///< 1 / rv^2
    float density;   ///< peak contribution
    bool smooth;     ///< Smooth kernel, else Sphere
};

/// The voxels whose centres may lie within the kernel radius of one particle: [lo, hi] per
/// axis, inclusive, and the particle's position `q` in index space. Computed by the same code
/// when binning and when splatting, so both agree to the bit.
struct Footprint {
    float q[3];
    int lo[3];
    int hi[3];
};

/// floor and ceil for |x| < 2^31, exact: truncate, then step toward -inf / +inf when that
/// moved x. Cheaper than std::floor / std::ceil without SSE4.1 (the baseline x86-64 target).
inline int floorInt(float x)
{
    const int i = static_cast<int>(x);
    return i - (x < static_cast<float>(i) ? 1 : 0);
}
inline int ceilInt(float x)
{
    const int i = static_cast<int>(x);
    return i + (x > static_cast<float>(i) ? 1 : 0);
}

/// Sets f.lo and f.hi from f.q.
inline void bounds(const Kernel& k, Footprint& f)
{
    for (int a = 0; a < 3; ++a) {
        f.lo[a] = ceilInt(f.q[a] - k.rv);
        f.hi[a] = floorInt(f.q[a] + k.rv);
    }
}

/// Fills `f` for a particle at index-space position q = p / voxel size (|q| < kMaxIndex).
inline void footprint(const float* p, const Kernel& k, Footprint& f)
{
    for (int a = 0; a < 3; ++a) f.q[a] = p[a] * k.invVoxel;
    bounds(k, f);
}

/// Floor division by the brick size, also for negative coordinates.
inline int brickOf(int voxel) { return voxel >> kBrickLog2; }

int bitsFor(std::int64_t extent)
{
    int b = 0;
    while ((std::int64_t(1) << b) < extent) ++b;
    return b;
}

/// Brick coordinates relative to the minimum, packed x-major (OpenVDB's order: z fastest).
struct KeyCodec {
    int min[3] = {0, 0, 0};
    int shiftX = 0;
    int shiftY = 0;
    int bits = 0;  ///< total key bits

    std::uint64_t encode(int lx, int ly, int lz) const
    {
        return (std::uint64_t(std::uint32_t(lx - min[0])) << shiftX) |
               (std::uint64_t(std::uint32_t(ly - min[1])) << shiftY) |
               std::uint64_t(std::uint32_t(lz - min[2]));
    }
    openvdb::Coord origin(std::uint64_t key) const
    {
        const std::uint64_t maskY = (std::uint64_t(1) << (shiftX - shiftY)) - 1;
        const std::uint64_t maskZ = (std::uint64_t(1) << shiftY) - 1;
        const int lx = static_cast<int>(key >> shiftX) + min[0];
        const int ly = static_cast<int>((key >> shiftY) & maskY) + min[1];
        const int lz = static_cast<int>(key & maskZ) + min[2];
        return openvdb::Coord(lx * kBrick, ly * kBrick, lz * kBrick);
    }
};

/// A sort entry: a brick key and the particle's index-space position, so that splatting
/// streams through memory instead of gathering particles at random (a cache miss each). The
/// index is not stored: entries are made in ascending particle index and the sort is stable.
template <class KeyT>
struct Entry {
    KeyT k;
    float q[3];
    std::uint64_t key() const { return k; }
};
using PackedEntry = Entry<std::uint32_t>;  ///< 16 bytes: keys of up to 32 bits (the usual case)
using WideEntry = Entry<std::uint64_t>;    ///< 24 bytes: huge sparse domains

/// Uninitialised scratch storage for trivially copyable T, on transparent huge pages where
/// the kernel allows them (madvise mode): a 5M-particle frame's entries take ~110 MB, and
/// faulting that in 4 KiB pages cost more than binning the particles.
template <class T>
class Scratch {
public:
    Scratch() = default;
    explicit Scratch(std::size_t n)
    {
        constexpr std::size_t kHuge = std::size_t(2) << 20;
        std::size_t bytes = std::max<std::size_t>(n * sizeof(T), 64);
        const std::size_t align = bytes >= kHuge ? kHuge : 64;
        bytes = (bytes + align - 1) / align * align;  // aligned_alloc wants a multiple
        mData = static_cast<T*>(std::aligned_alloc(align, bytes));
        if (!mData) throw std::bad_alloc();
        if (align == kHuge) util::adviseHugePages(mData, bytes);
    }
    ~Scratch() { std::free(mData); }
    Scratch(Scratch&& other) noexcept : mData(other.mData) { other.mData = nullptr; }
    Scratch(const Scratch&) = delete;
    Scratch& operator=(const Scratch&) = delete;
    void swap(Scratch& other) { std::swap(mData, other.mData); }
    void reset()
    {
        std::free(mData);
        mData = nullptr;
    }
    T* get() const { return mData; }
    T& operator[](std::size_t i) const { return mData[i]; }

private:
    T* mData = nullptr;
};

std::size_t chunkCount(std::size_t n) { return (n + kChunk - 1) / kChunk; }

/// Stable LSD radix sort of `a` by key (11-bit digits over `keyBits` bits). Entries start in
/// ascending particle index, so the result is ordered by (key, index): unique, whatever the
/// thread count. `tmp` is scratch of the same size; the result ends in `a`.
template <class E>
void radixSortByKey(Scratch<E>& a, Scratch<E>& tmp, std::size_t n, int keyBits)
{
    constexpr int kDigit = 11;
    constexpr std::size_t kBuckets = std::size_t(1) << kDigit;
    const std::size_t blocks = chunkCount(n);
    std::vector<std::uint32_t> hist(blocks * kBuckets);
    for (int shift = 0; shift < keyBits; shift += kDigit) {
        const E* src = a.get();
        E* dst = tmp.get();
        tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
            std::uint32_t* row = &hist[b * kBuckets];
            std::fill(row, row + kBuckets, 0u);
            const std::size_t end = std::min(n, (b + 1) * kChunk);
            for (std::size_t i = b * kChunk; i < end; ++i)
                ++row[(src[i].key() >> shift) & (kBuckets - 1)];
        });
        // Exclusive prefix, digit-major then block: each block scatters into its own slots.
        std::uint32_t running = 0;
        bool trivial = false;
        for (std::size_t d = 0; d < kBuckets && !trivial; ++d) {
            const std::uint32_t before = running;
            for (std::size_t b = 0; b < blocks; ++b) {
                const std::uint32_t c = hist[b * kBuckets + d];
                hist[b * kBuckets + d] = running;
                running += c;
            }
            trivial = before == 0 && running == n;  // one digit holds everything: pass is a no-op
        }
        if (trivial) continue;
        tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
            std::uint32_t* row = &hist[b * kBuckets];
            const std::size_t end = std::min(n, (b + 1) * kChunk);
            for (std::size_t i = b * kChunk; i < end; ++i)
                dst[row[(src[i].key() >> shift) & (kBuckets - 1)]++] = src[i];
        });
        a.swap(tmp);
    }
}

/// The per-brick accumulator: 32 x 32 rows along z, each padded by kPad voxels on both sides
/// so a fixed-width window of voxels along z can be added without clipping (what falls in
/// the padding belongs to a neighbour brick and is dropped). 192 KiB: fits the L2 cache.
constexpr int kPad = 8;
constexpr int kRow = kBrick + 2 * kPad;
constexpr int kAccSize = kBrick * kBrick * kRow;
inline int accIndex(int x, int y, int z) { return ((x << kBrickLog2) + y) * kRow + kPad + z; }

/// Four floats in an SSE register (GCC/Clang vector extension): the same IEEE operations as
/// the scalar code, lane by lane, so the sums are bit-identical.
using Float4 = float __attribute__((vector_size(16)));

inline Float4 load4(const float* p)
{
    Float4 v;
    std::memcpy(&v, p, sizeof(v));
    return v;
}
inline void store4(float* p, Float4 v) { std::memcpy(p, &v, sizeof(v)); }

/// Adds every entry's particle, clipped to the brick at `origin` in x and y, into `acc`, in the
/// entries' order. Along z it adds a fixed window of W voxels from the footprint's first
/// (W >= the widest footprint): voxels past the footprint get exactly +0, so the sums are
/// those of the clipped loop, without its unpredictable branches, and the window vectorises.
template <int W, bool Smooth, class E>
void splatWindow(const E* begin, const E* end, const Kernel& k, const openvdb::Coord& origin,
                 float* acc)
{
    const int ox = origin.x(), oy = origin.y(), oz = origin.z();
    // Locals, so the compiler knows the stores into acc cannot change them (vectorises).
    const float invRv2 = k.invRv2, rv2 = k.rv2, density = k.density;
    for (const E* e = begin; e != end; ++e) {
        Footprint f;
        f.q[0] = e->q[0];
        f.q[1] = e->q[1];
        f.q[2] = e->q[2];
        bounds(k, f);  // as when binning, to the bit
        const int x0 = std::max(f.lo[0], ox), x1 = std::min(f.hi[0], ox + kBrickMax);
        const int y0 = std::max(f.lo[1], oy), y1 = std::min(f.hi[1], oy + kBrickMax);
        float dz2[W];
        for (int w = 0; w < W; ++w) {
            const float dz = static_cast<float>(f.lo[2] + w) - f.q[2];
            dz2[w] = dz * dz;
        }
        for (int x = x0; x <= x1; ++x) {
            const float dx = static_cast<float>(x) - f.q[0];
            for (int y = y0; y <= y1; ++y) {
                const float dy = static_cast<float>(y) - f.q[1];
                const float dxy2 = dx * dx + dy * dy;
                float* __restrict row = acc + accIndex(x - ox, y - oy, f.lo[2] - oz);
                if (Smooth) {
                    const Float4 zero = {0.0f, 0.0f, 0.0f, 0.0f};
                    for (int w = 0; w < W; w += 4) {
                        Float4 t = 1.0f - (dxy2 + load4(dz2 + w)) * invRv2;
                        t = t > zero ? t : zero;
                        store4(row + w, load4(row + w) + density * (t * t * t));
                    }
                    continue;
                }
                for (int w = 0; w < W; ++w) {
                    if (Smooth) {
                        // A select rather than a branch: adding +0 changes nothing.
                        float t = 1.0f - (dxy2 + dz2[w]) * invRv2;
                        t = t > 0.0f ? t : 0.0f;
                        row[w] += density * (t * t * t);
                    } else {
                        row[w] += dxy2 + dz2[w] < rv2 ? density : 0.0f;
                    }
                }
            }
        }
    }
}

/// The same sums for any radius (up to 32 voxels), clipped in all three axes.
template <class E>
void splatClipped(const E* begin, const E* end, const Kernel& k, const openvdb::Coord& origin,
                  float* acc)
{
    const int ox = origin.x(), oy = origin.y(), oz = origin.z();
    for (const E* e = begin; e != end; ++e) {
        Footprint f;
        f.q[0] = e->q[0];
        f.q[1] = e->q[1];
        f.q[2] = e->q[2];
        bounds(k, f);
        const int x0 = std::max(f.lo[0], ox), x1 = std::min(f.hi[0], ox + kBrickMax);
        const int y0 = std::max(f.lo[1], oy), y1 = std::min(f.hi[1], oy + kBrickMax);
        const int z0 = std::max(f.lo[2], oz), z1 = std::min(f.hi[2], oz + kBrickMax);
        for (int x = x0; x <= x1; ++x) {
            const float dx = static_cast<float>(x) - f.q[0];
            for (int y = y0; y <= y1; ++y) {
                const float dy = static_cast<float>(y) - f.q[1];
                const float dxy2 = dx * dx + dy * dy;
                float* row = acc + accIndex(x - ox, y - oy, 0);
                for (int z = z0; z <= z1; ++z) {
                    const float dz = static_cast<float>(z) - f.q[2];
                    if (k.smooth) {
                        const float t = std::max(1.0f - (dxy2 + dz * dz) * k.invRv2, 0.0f);
                        row[z - oz] += k.density * (t * t * t);
                    } else {
                        row[z - oz] += dxy2 + dz * dz < k.rv2 ? k.density : 0.0f;
                    }
                }
            }
        }
    }
}

template <class E>
void splatBrick(const E* begin, const E* end, const Kernel& k, const openvdb::Coord& origin,
                float* acc)
{
    // Widest footprint along an axis: floor(q + rv) - ceil(q - rv) + 1 <= 2 rv + 1, plus slack
    // for the rounding of q +- rv (at most 1/8 voxel at |q| < 2^20).
    const float width = 2.0f * k.rv + 1.25f;
    if (width <= 4.0f) {
        k.smooth ? splatWindow<4, true>(begin, end, k, origin, acc)
                 : splatWindow<4, false>(begin, end, k, origin, acc);
    } else if (width <= 8.0f) {
        k.smooth ? splatWindow<8, true>(begin, end, k, origin, acc)
                 : splatWindow<8, false>(begin, end, k, origin, acc);
    } else {
        splatClipped(begin, end, k, origin, acc);
    }
}

/// Calls fn(key) for each brick the footprint touches, in ascending key order.
template <class F>
inline void forEachBrick(const Footprint& f, const KeyCodec& codec, F&& fn)
{
    for (int lx = brickOf(f.lo[0]); lx <= brickOf(f.hi[0]); ++lx)
        for (int ly = brickOf(f.lo[1]); ly <= brickOf(f.hi[1]); ++ly)
            for (int lz = brickOf(f.lo[2]); lz <= brickOf(f.hi[2]); ++lz)
                fn(codec.encode(lx, ly, lz));
}

/// Particles per block of the counting sort: few blocks, so that their per-brick histograms
/// stay small, but fixed, so that the order within a brick never depends on the threads.
constexpr std::size_t kCountBlock = std::size_t(1) << 19;
/// Largest histogram (blocks x 2^key bits counters) for the counting sort; beyond it (huge
/// sparse domains) the entries are radix sorted instead, in memory that follows the entries.
constexpr std::size_t kMaxCountCells = std::size_t(1) << 23;

bool countingSortFits(std::size_t count, const KeyCodec& codec)
{
    const std::size_t blocks = (count + kCountBlock - 1) / kCountBlock;
    return codec.bits <= 23 && blocks <= (kMaxCountCells >> codec.bits);
}

/// One entry per (particle, brick it touches), grouped by brick key in ascending order and by
/// particle index within a brick. `starts` gets the first entry of each brick, then n.
template <class E>
Scratch<E> binByBrick(const float* xyz, std::size_t count, const Kernel& k, const KeyCodec& codec,
                      std::vector<std::size_t>& starts)
{
    using KeyT = decltype(E::k);
    const auto tooMany = [] {
        throw std::invalid_argument("voxelize: more than 2^32 - 1 particle-brick pairs");
    };
    if (countingSortFits(count, codec)) {
        // Counting sort: a histogram per block over the dense key space (the brick bounding
        // box, small next to the particles), offsets brick-major then block, then a scatter
        // that writes every entry once in its final place.
        const std::size_t blocks = (count + kCountBlock - 1) / kCountBlock;
        const std::size_t cells = std::size_t(1) << codec.bits;
        std::vector<std::uint32_t> hist(blocks * cells, 0u);
        tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
            std::uint32_t* row = &hist[b * cells];
            const std::size_t end = std::min(count, (b + 1) * kCountBlock);
            for (std::size_t i = b * kCountBlock; i < end; ++i) {
                Footprint f;
                footprint(xyz + 3 * i, k, f);
                forEachBrick(f, codec, [row](std::uint64_t key) { ++row[key]; });
            }
        });
        std::uint64_t running = 0;
        for (std::size_t key = 0; key < cells; ++key) {
            const std::uint64_t before = running;
            for (std::size_t b = 0; b < blocks; ++b) {
                const std::uint32_t c = hist[b * cells + key];
                hist[b * cells + key] = static_cast<std::uint32_t>(running);
                running += c;
            }
            if (running > std::numeric_limits<std::uint32_t>::max()) tooMany();
            if (running != before) starts.push_back(before);
        }
        const std::size_t n = running;
        Scratch<E> entries(n);
        tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
            std::uint32_t* row = &hist[b * cells];
            E* out = entries.get();
            const std::size_t end = std::min(count, (b + 1) * kCountBlock);
            for (std::size_t i = b * kCountBlock; i < end; ++i) {
                Footprint f;
                footprint(xyz + 3 * i, k, f);
                forEachBrick(f, codec, [&](std::uint64_t key) {
                    out[row[key]++] = E{static_cast<KeyT>(key), {f.q[0], f.q[1], f.q[2]}};
                });
            }
        });
        starts.push_back(n);
        return entries;
    }

    // Radix sort: entries made in particle order, then a stable sort by key.
    const std::size_t chunks = chunkCount(count);
    std::vector<std::size_t> offsets(chunks + 1, 0);
    tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
        std::size_t touched = 0;
        const std::size_t end = std::min(count, (c + 1) * kChunk);
        for (std::size_t i = c * kChunk; i < end; ++i) {
            Footprint f;
            footprint(xyz + 3 * i, k, f);
            forEachBrick(f, codec, [&touched](std::uint64_t) { ++touched; });
        }
        offsets[c + 1] = touched;
    });
    for (std::size_t c = 0; c < chunks; ++c) offsets[c + 1] += offsets[c];
    const std::size_t n = offsets[chunks];
    if (n > std::numeric_limits<std::uint32_t>::max()) tooMany();
    Scratch<E> entries(n);
    tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
        E* out = entries.get() + offsets[c];
        const std::size_t end = std::min(count, (c + 1) * kChunk);
        for (std::size_t i = c * kChunk; i < end; ++i) {
            Footprint f;
            footprint(xyz + 3 * i, k, f);
            forEachBrick(f, codec, [&](std::uint64_t key) {
                *out++ = E{static_cast<KeyT>(key), {f.q[0], f.q[1], f.q[2]}};
            });
        }
    });
    {
        Scratch<E> scratch(n);
        radixSortByKey(entries, scratch, n, codec.bits);
    }
    // Where each brick's run of entries starts; found per block, concatenated in block order.
    const std::size_t blocks = chunkCount(n);
    std::vector<std::vector<std::size_t>> blockStarts(blocks);
    tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
        const std::size_t end = std::min(n, (b + 1) * kChunk);
        for (std::size_t i = b * kChunk; i < end; ++i)
            if (i == 0 || entries[i].key() != entries[i - 1].key()) blockStarts[b].push_back(i);
    });
    for (const auto& s : blockStarts) starts.insert(starts.end(), s.begin(), s.end());
    starts.push_back(n);
    return entries;
}

template <class E>
openvdb::FloatGrid::Ptr voxelizeWith(const float* xyz, std::size_t count, const Kernel& k,
                                     bool clamp, const KeyCodec& codec,
                                     const std::function<void()>& checkCancelled)
{
    std::vector<std::size_t> starts;
    Scratch<E> entries = binByBrick<E>(xyz, count, k, codec, starts);
    if (checkCancelled) checkCancelled();
    const std::size_t brickCount = starts.size() - 1;

    // One task per brick sums its particles in ascending index order: the float rounding is
    // the same for any thread count.
    constexpr int kLeavesPerBrick = (kBrick / 8) * (kBrick / 8) * (kBrick / 8);
    std::vector<std::unique_ptr<LeafT>> leaves(brickCount * kLeavesPerBrick);
    tbb::enumerable_thread_specific<std::vector<float>> accumulators(
        [] { return std::vector<float>(kAccSize); });
    tbb::parallel_for(std::size_t(0), brickCount, [&](std::size_t b) {
        float* acc = accumulators.local().data();
        std::fill(acc, acc + kAccSize, 0.0f);
        const openvdb::Coord origin = codec.origin(entries[starts[b]].key());
        splatBrick(entries.get() + starts[b], entries.get() + starts[b + 1], k, origin, acc);
        std::unique_ptr<LeafT>* out = &leaves[b * kLeavesPerBrick];
        for (int x = 0; x < kBrick; x += 8)
            for (int y = 0; y < kBrick; y += 8)
                for (int z = 0; z < kBrick; z += 8)
                    *out++ = leafFromDense(acc + accIndex(x, y, z), kBrick * kRow, kRow,
                                           origin + openvdb::Coord(x, y, z), clamp);
    });
    entries.reset();

    auto grid = openvdb::FloatGrid::create(0.0f);
    openvdb::FloatTree& tree = grid->tree();
    for (auto& leaf : leaves)
        if (leaf) tree.addLeaf(leaf.release());
    if (checkCancelled) checkCancelled();
    return grid;
}

}  // namespace

std::uint64_t voxelizeMemoryBound(std::size_t count, const double extentVoxels[3],
                                  double radiusVoxels)
{
    // In doubles: the point is to refuse sizes whose products overflow 64-bit integers.
    // The level above the leaves: 128^3 voxels.
    using Internal1 = openvdb::FloatTree::RootNodeType::ChildNodeType::ChildNodeType;
    const double n = static_cast<double>(count);
    const double span = 2.0 * radiusVoxels + 1.0;
    double bricksPerSplat = 1.0, leavesPerSplat = 1.0, boundsLeaves = 1.0;
    double nodesPerSplat = 1.0, boundsNodes = 1.0;
    for (int a = 0; a < 3; ++a) {
        bricksPerSplat *= std::ceil(span / kBrick) + 1.0;
        leavesPerSplat *= std::ceil(span / LeafT::DIM) + 1.0;
        boundsLeaves *= std::ceil((extentVoxels[a] + span) / LeafT::DIM) + 1.0;
        nodesPerSplat *= std::ceil(span / Internal1::DIM) + 1.0;
        boundsNodes *= std::ceil((extentVoxels[a] + span) / Internal1::DIM) + 1.0;
    }
    const double entries = n * bricksPerSplat * 2.0 * sizeof(WideEntry);  // entries + scratch
    const double leafBytes = sizeof(LeafT) + LeafT::SIZE * sizeof(float);
    const double leaves = std::min(n * leavesPerSplat, boundsLeaves) * leafBytes;
    const double nodes = std::min(n * nodesPerSplat, boundsNodes) * sizeof(Internal1);
    const double total = entries + leaves + nodes;
    return total >= 1.8e19 ? std::numeric_limits<std::uint64_t>::max()
                           : static_cast<std::uint64_t>(total);
}

VoxelKernel voxelKernelFromName(const std::string& name)
{
    if (name == "smooth") return VoxelKernel::Smooth;
    if (name == "sphere") return VoxelKernel::Sphere;
    if (name == "gaussian") return VoxelKernel::Gaussian;
    throw std::invalid_argument("unknown voxel kernel '" + name + "' (smooth, sphere, gaussian)");
}

double kernelIntegral(VoxelKernel kernel, double radius)
{
    const double pi = 3.14159265358979323846;
    const double r3 = radius * radius * radius;
    // Smooth: 4 pi R^3 * int_0^1 (1 - u^2)^3 u^2 du = 4 pi R^3 * 16/315.
    // Gaussian: sigma is chosen to give the same integral (GaussianSplat.h).
    return kernel == VoxelKernel::Sphere ? 4.0 * pi * r3 / 3.0 : 64.0 * pi * r3 / 315.0;
}

void checkVoxelizeSettings(const VoxelizeSettings& settings)
{
    if (!(settings.voxelSize > 0.0) || !std::isfinite(settings.voxelSize))
        throw std::invalid_argument("voxelize: voxel size must be > 0");
    if (!(settings.radius > 0.0) || settings.radius > 32.0 * settings.voxelSize)
        throw std::invalid_argument("voxelize: radius must be > 0 and at most 32 voxels");
    if (!(settings.density >= 0.0) || !std::isfinite(settings.density))
        throw std::invalid_argument("voxelize: density must be finite and >= 0");
}

openvdb::FloatGrid::Ptr voxelizeParticles(const float* xyz, std::size_t count,
                                          const VoxelizeSettings& settings,
                                          const std::function<void()>& checkCancelled)
{
    checkVoxelizeSettings(settings);
    if (count > std::numeric_limits<std::uint32_t>::max())
        throw std::invalid_argument("voxelize: more than 2^32 - 1 particles");
    if (settings.kernel == VoxelKernel::Gaussian) {
        GaussianSplatter splatter(settings);
        // Fixed chunks only for balance: the deposit's sums do not depend on the order.
        tbb::parallel_for(std::size_t(0), chunkCount(count), [&](std::size_t c) {
            splatter.add(xyz + 3 * c * kChunk, std::min(kChunk, count - c * kChunk));
        });
        if (checkCancelled) checkCancelled();
        return splatter.finish(checkCancelled);
    }

    Kernel k;
    k.invVoxel = static_cast<float>(1.0 / settings.voxelSize);
    k.rv = static_cast<float>(settings.radius / settings.voxelSize);
    k.rv2 = k.rv * k.rv;
    k.invRv2 = 1.0f / k.rv2;
    k.density = static_cast<float>(settings.density);
    k.smooth = settings.kernel == VoxelKernel::Smooth;

    // Pass 1: validity and the bounds of q = p / voxel size. The brick bounds follow from
    // them by the same (monotonic) float operations as each particle's footprint.
    const std::size_t chunks = chunkCount(count);
    struct ChunkInfo {
        float lo[3] = {kMaxIndex, kMaxIndex, kMaxIndex};
        float hi[3] = {-kMaxIndex, -kMaxIndex, -kMaxIndex};
        bool bad = false;
    };
    std::vector<ChunkInfo> info(chunks);
    tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
        ChunkInfo& ci = info[c];
        bool bad = false;
        const std::size_t end = std::min(count, (c + 1) * kChunk);
        for (std::size_t i = c * kChunk; i < end; ++i) {
            for (int a = 0; a < 3; ++a) {
                const float q = xyz[3 * i + a] * k.invVoxel;
                bad |= !(std::fabs(q) < kMaxIndex);  // also catches NaN
                ci.lo[a] = std::min(ci.lo[a], q);
                ci.hi[a] = std::max(ci.hi[a], q);
            }
        }
        ci.bad = bad;
    });
    ChunkInfo all;
    for (std::size_t c = 0; c < chunks; ++c) {
        if (info[c].bad)
            throw std::invalid_argument(
                "voxelize: a particle position is not finite or lies "
                "beyond 2^20 voxels from the origin");
        for (int a = 0; a < 3; ++a) {
            all.lo[a] = std::min(all.lo[a], info[c].lo[a]);
            all.hi[a] = std::max(all.hi[a], info[c].hi[a]);
        }
    }
    if (checkCancelled) checkCancelled();
    if (settings.maxBytes != 0 && count != 0) {
        const double extent[3] = {double(all.hi[0]) - all.lo[0], double(all.hi[1]) - all.lo[1],
                                  double(all.hi[2]) - all.lo[2]};
        const std::uint64_t bound = voxelizeMemoryBound(count, extent, k.rv);
        if (bound > settings.maxBytes)
            throw VoxelizeTooLarge(
                "voxelize: " + std::to_string(count) + " particles with a radius of " +
                std::to_string(k.rv) + " voxels would need up to " + std::to_string(bound >> 20) +
                " MiB, over the limit of " + std::to_string(settings.maxBytes >> 20) +
                " MiB; use larger voxels (voxelSize) or a smaller radius");
    }

    openvdb::FloatGrid::Ptr grid;
    if (count == 0) {
        grid = openvdb::FloatGrid::create(0.0f);
    } else {
        KeyCodec codec;
        int bits[3];
        for (int a = 0; a < 3; ++a) {
            codec.min[a] = brickOf(ceilInt(all.lo[a] - k.rv));
            const int max = brickOf(floorInt(all.hi[a] + k.rv));
            bits[a] = bitsFor(std::int64_t(max) - codec.min[a] + 1);
        }
        codec.shiftY = bits[2];
        codec.shiftX = bits[1] + bits[2];
        codec.bits = bits[0] + bits[1] + bits[2];
        grid = codec.bits <= 32
                   ? voxelizeWith<PackedEntry>(xyz, count, k, settings.clamp, codec, checkCancelled)
                   : voxelizeWith<WideEntry>(xyz, count, k, settings.clamp, codec, checkCancelled);
    }
    grid->setName("density");
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(settings.voxelSize));
    return grid;
}

VoxelFilter voxelFilterFromName(const std::string& name)
{
    if (name == "none") return VoxelFilter::None;
    if (name == "mean") return VoxelFilter::Mean;
    if (name == "gaussian") return VoxelFilter::Gaussian;
    if (name == "median") return VoxelFilter::Median;
    throw std::invalid_argument("unknown volume filter '" + name +
                                "' (none, mean, gaussian, median)");
}

void filterVolume(openvdb::FloatGrid& grid, VoxelFilter filter, int width, int iterations)
{
    if (filter == VoxelFilter::None || iterations <= 0 || width <= 0) return;
    openvdb::tools::Filter<openvdb::FloatGrid> f(grid);
    switch (filter) {
        case VoxelFilter::Mean:
            f.mean(width, iterations);
            break;
        case VoxelFilter::Gaussian:
            f.gaussian(width, iterations);
            break;
        case VoxelFilter::Median:
            f.median(width, iterations);
            break;
        case VoxelFilter::None:
            break;
    }
}

}  // namespace cg::algo
