#include "nodes/algo/Voxelize.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

#include <openvdb/tools/Filter.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace cg::algo {

namespace {

using LeafT = openvdb::FloatTree::LeafNodeType;
static_assert(LeafT::LOG2DIM == 3, "the binning below assumes 8^3-voxel leaves");
constexpr int kLeafLog2 = 3;
constexpr int kLeafMax = 7;  // last voxel of a leaf along an axis, relative to its origin

/// Fixed work unit (particles or sort entries) so the partition never depends on the thread
/// count; only the leaf sums need a fixed order, but fixed chunks keep every phase reproducible.
constexpr std::size_t kChunk = std::size_t(1) << 16;
/// Index coordinates are limited to +-2^20 voxels so three leaf coordinates pack into 64 bits.
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

/// True when the particle's index coordinates are finite and within +-kMaxIndex.
inline bool inRange(const float* p, const Kernel& k)
{
    for (int a = 0; a < 3; ++a)
        if (!(std::fabs(p[a] * k.invVoxel) < kMaxIndex)) return false;  // also catches NaN
    return true;
}

/// Sets f.lo and f.hi from f.q.
inline void bounds(const Kernel& k, Footprint& f)
{
    for (int a = 0; a < 3; ++a) {
        f.lo[a] = static_cast<int>(std::ceil(f.q[a] - k.rv));
        f.hi[a] = static_cast<int>(std::floor(f.q[a] + k.rv));
    }
}

/// Fills `f` for a particle at index-space position q = p / voxel size (inRange(p, k)).
inline void footprint(const float* p, const Kernel& k, Footprint& f)
{
    for (int a = 0; a < 3; ++a) f.q[a] = p[a] * k.invVoxel;
    bounds(k, f);
}

/// Floor division by the leaf size, also for negative coordinates.
inline int leafOf(int voxel) { return voxel >> kLeafLog2; }

int bitsFor(std::int64_t extent)
{
    int b = 0;
    while ((std::int64_t(1) << b) < extent) ++b;
    return b;
}

/// Leaf coordinates relative to the minimum, packed x-major (OpenVDB's own order: z fastest).
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
        return openvdb::Coord(lx * 8, ly * 8, lz * 8);
    }
};

/// A sort entry: a leaf key and the particle's index-space position, so that splatting
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

std::size_t chunkCount(std::size_t n) { return (n + kChunk - 1) / kChunk; }

/// Stable LSD radix sort of `a` by key (11-bit digits over `keyBits` bits). Entries start in
/// ascending particle index, so the result is ordered by (key, index): unique, whatever the
/// thread count. `tmp` is scratch of the same size; the result ends in `a`.
template <class E>
void radixSortByKey(std::unique_ptr<E[]>& a, std::unique_ptr<E[]>& tmp, std::size_t n, int keyBits)
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
        std::swap(a, tmp);
    }
}

/// The per-leaf accumulator: 8 x 8 rows along z, each padded by kPad voxels on both sides so a
/// fixed-width window of voxels along z can be added without clipping (what falls in the
/// padding belongs to a neighbour leaf and is dropped).
constexpr int kPad = 8;
constexpr int kRow = 8 + 2 * kPad;
constexpr int kAccSize = 64 * kRow;
inline int accIndex(int x, int y, int z) { return ((x << 3) + y) * kRow + kPad + z; }

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

/// Adds every entry's particle, clipped to the leaf at `origin` in x and y, into `acc`, in the
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
        const int x0 = std::max(f.lo[0], ox), x1 = std::min(f.hi[0], ox + kLeafMax);
        const int y0 = std::max(f.lo[1], oy), y1 = std::min(f.hi[1], oy + kLeafMax);
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
        const int x0 = std::max(f.lo[0], ox), x1 = std::min(f.hi[0], ox + kLeafMax);
        const int y0 = std::max(f.lo[1], oy), y1 = std::min(f.hi[1], oy + kLeafMax);
        const int z0 = std::max(f.lo[2], oz), z1 = std::min(f.hi[2], oz + kLeafMax);
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
void splatLeaf(const E* begin, const E* end, const Kernel& k, const openvdb::Coord& origin,
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

template <class E>
openvdb::FloatGrid::Ptr voxelizeWith(const float* xyz, std::size_t count, const Kernel& k,
                                     bool clamp, const KeyCodec& codec,
                                     const std::vector<std::size_t>& chunkEntries,
                                     const std::function<void()>& checkCancelled)
{
    // Offsets of each particle chunk's entries.
    const std::size_t chunks = chunkEntries.size();
    std::vector<std::size_t> offsets(chunks + 1, 0);
    for (std::size_t c = 0; c < chunks; ++c) offsets[c + 1] = offsets[c] + chunkEntries[c];
    const std::size_t n = offsets[chunks];
    if (n > std::numeric_limits<std::uint32_t>::max())
        throw std::invalid_argument("voxelize: more than 2^32 - 1 particle-leaf pairs");

    // Uninitialised on purpose: every slot is written below.
    std::unique_ptr<E[]> entries(new E[n]);
    std::unique_ptr<E[]> scratch(new E[n]);
    tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
        E* out = entries.get() + offsets[c];
        const std::size_t end = std::min(count, (c + 1) * kChunk);
        for (std::size_t i = c * kChunk; i < end; ++i) {
            Footprint f;
            footprint(xyz + 3 * i, k, f);
            for (int lx = leafOf(f.lo[0]); lx <= leafOf(f.hi[0]); ++lx)
                for (int ly = leafOf(f.lo[1]); ly <= leafOf(f.hi[1]); ++ly)
                    for (int lz = leafOf(f.lo[2]); lz <= leafOf(f.hi[2]); ++lz)
                        *out++ = E{static_cast<decltype(E::k)>(codec.encode(lx, ly, lz)),
                                   {f.q[0], f.q[1], f.q[2]}};
        }
    });
    radixSortByKey(entries, scratch, n, codec.bits);
    scratch.reset();
    if (checkCancelled) checkCancelled();

    // Where each leaf's run of entries starts; found per block, concatenated in block order.
    const std::size_t blocks = chunkCount(n);
    std::vector<std::vector<std::size_t>> blockStarts(blocks);
    tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
        const std::size_t end = std::min(n, (b + 1) * kChunk);
        for (std::size_t i = b * kChunk; i < end; ++i)
            if (i == 0 || entries[i].key() != entries[i - 1].key()) blockStarts[b].push_back(i);
    });
    std::vector<std::size_t> starts;
    for (const auto& s : blockStarts) starts.insert(starts.end(), s.begin(), s.end());
    blockStarts.clear();
    starts.push_back(n);
    const std::size_t leafCount = starts.size() - 1;

    // One task per leaf sums its particles in ascending index order: the float rounding is
    // the same for any thread count.
    std::vector<std::unique_ptr<LeafT>> leaves(leafCount);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leafCount, 16),
                      [&](const tbb::blocked_range<std::size_t>& r) {
        alignas(64) float acc[kAccSize];
        for (std::size_t l = r.begin(); l != r.end(); ++l) {
            std::fill(acc, acc + kAccSize, 0.0f);
            const openvdb::Coord origin = codec.origin(entries[starts[l]].key());
            splatLeaf(entries.get() + starts[l], entries.get() + starts[l + 1], k, origin, acc);
            auto leaf = std::make_unique<LeafT>(origin, 0.0f, false);
            bool any = false;
            for (openvdb::Index i = 0; i < LeafT::SIZE; ++i) {
                const float v = acc[accIndex(int(i >> 6), int((i >> 3) & 7), int(i & 7))];
                if (!(v > 0.0f)) continue;
                leaf->setValueOn(i, clamp ? std::min(v, 1.0f) : v);
                any = true;
            }
            if (any) leaves[l] = std::move(leaf);
        }
    });
    entries.reset();
    if (checkCancelled) checkCancelled();

    auto grid = openvdb::FloatGrid::create(0.0f);
    openvdb::FloatTree& tree = grid->tree();
    for (auto& leaf : leaves)
        if (leaf) tree.addLeaf(leaf.release());
    return grid;
}

}  // namespace

VoxelKernel voxelKernelFromName(const std::string& name)
{
    if (name == "smooth") return VoxelKernel::Smooth;
    if (name == "sphere") return VoxelKernel::Sphere;
    throw std::invalid_argument("unknown voxel kernel '" + name + "' (smooth, sphere)");
}

double kernelIntegral(VoxelKernel kernel, double radius)
{
    const double pi = 3.14159265358979323846;
    const double r3 = radius * radius * radius;
    // Smooth: 4 pi R^3 * int_0^1 (1 - u^2)^3 u^2 du = 4 pi R^3 * 16/315.
    return kernel == VoxelKernel::Smooth ? 64.0 * pi * r3 / 315.0 : 4.0 * pi * r3 / 3.0;
}

openvdb::FloatGrid::Ptr voxelizeParticles(const float* xyz, std::size_t count,
                                          const VoxelizeSettings& settings,
                                          const std::function<void()>& checkCancelled)
{
    if (!(settings.voxelSize > 0.0) || !std::isfinite(settings.voxelSize))
        throw std::invalid_argument("voxelize: voxel size must be > 0");
    if (!(settings.radius > 0.0) || settings.radius > 32.0 * settings.voxelSize)
        throw std::invalid_argument("voxelize: radius must be > 0 and at most 32 voxels");
    if (!(settings.density >= 0.0) || !std::isfinite(settings.density))
        throw std::invalid_argument("voxelize: density must be finite and >= 0");
    if (count > std::numeric_limits<std::uint32_t>::max())
        throw std::invalid_argument("voxelize: more than 2^32 - 1 particles");

    Kernel k;
    k.invVoxel = static_cast<float>(1.0 / settings.voxelSize);
    k.rv = static_cast<float>(settings.radius / settings.voxelSize);
    k.rv2 = k.rv * k.rv;
    k.invRv2 = 1.0f / k.rv2;
    k.density = static_cast<float>(settings.density);
    k.smooth = settings.kernel == VoxelKernel::Smooth;

    // Pass 1: entries per chunk (one per leaf a particle touches) and the leaf bounds.
    const std::size_t chunks = chunkCount(count);
    struct ChunkInfo {
        std::size_t entries = 0;
        int min[3] = {std::numeric_limits<int>::max(), std::numeric_limits<int>::max(),
                      std::numeric_limits<int>::max()};
        int max[3] = {std::numeric_limits<int>::min(), std::numeric_limits<int>::min(),
                      std::numeric_limits<int>::min()};
        bool bad = false;
    };
    std::vector<ChunkInfo> info(chunks);
    tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
        ChunkInfo& ci = info[c];
        const std::size_t end = std::min(count, (c + 1) * kChunk);
        for (std::size_t i = c * kChunk; i < end; ++i) {
            if (!inRange(xyz + 3 * i, k)) {
                ci.bad = true;
                return;
            }
            Footprint f;
            footprint(xyz + 3 * i, k, f);
            std::size_t touched = 1;
            for (int a = 0; a < 3; ++a) {
                const int l0 = leafOf(f.lo[a]);
                const int l1 = leafOf(f.hi[a]);
                touched *= static_cast<std::size_t>(l1 - l0 + 1);
                ci.min[a] = std::min(ci.min[a], l0);
                ci.max[a] = std::max(ci.max[a], l1);
            }
            ci.entries += touched;
        }
    });
    ChunkInfo all;
    std::vector<std::size_t> chunkEntries(chunks);
    for (std::size_t c = 0; c < chunks; ++c) {
        if (info[c].bad)
            throw std::invalid_argument("voxelize: a particle position is not finite or lies "
                                        "beyond 2^20 voxels from the origin");
        chunkEntries[c] = info[c].entries;
        for (int a = 0; a < 3; ++a) {
            all.min[a] = std::min(all.min[a], info[c].min[a]);
            all.max[a] = std::max(all.max[a], info[c].max[a]);
        }
    }
    if (checkCancelled) checkCancelled();

    openvdb::FloatGrid::Ptr grid;
    if (count == 0) {
        grid = openvdb::FloatGrid::create(0.0f);
    } else {
        KeyCodec codec;
        int bits[3];
        for (int a = 0; a < 3; ++a) {
            codec.min[a] = all.min[a];
            bits[a] = bitsFor(std::int64_t(all.max[a]) - all.min[a] + 1);
        }
        codec.shiftY = bits[2];
        codec.shiftX = bits[1] + bits[2];
        codec.bits = bits[0] + bits[1] + bits[2];
        grid = codec.bits <= 32
                   ? voxelizeWith<PackedEntry>(xyz, count, k, settings.clamp, codec, chunkEntries,
                                               checkCancelled)
                   : voxelizeWith<WideEntry>(xyz, count, k, settings.clamp, codec, chunkEntries,
                                             checkCancelled);
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
    case VoxelFilter::Mean: f.mean(width, iterations); break;
    case VoxelFilter::Gaussian: f.gaussian(width, iterations); break;
    case VoxelFilter::Median: f.median(width, iterations); break;
    case VoxelFilter::None: break;
    }
}

}  // namespace cg::algo
