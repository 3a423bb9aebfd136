#include "algo/volume/GaussianSplat.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iterator>
#include <mutex>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "algo/volume/CoordKey.h"
#include "algo/volume/LeafFromDense.h"
#include "algo/volume/RecentLookup.h"

namespace cg::algo {

namespace {

using LeafT = openvdb::FloatTree::LeafNodeType;

/// The deposit is kept in blocks of 16^3 voxels (38 KiB of weights): small enough that thin
/// sparse clouds do not pay for much empty space, large enough that a hash lookup is rare.
/// Each block stores one more layer on its +x, +y and +z sides (17^3 voxels), so that all 8
/// corners of a particle whose first corner lies in the block land in it: one lookup a
/// particle. The layer belongs to the neighbouring blocks and is added into them in finish.
constexpr int kBlockLog2 = 4;
constexpr int kBlock = 1 << kBlockLog2;
constexpr int kStored = kBlock + 1;  ///< voxels a side a block stores, its halo layer included
constexpr int kBlockVoxels = kStored * kStored * kStored;
/// The blur writes bricks of 32^3 voxels (4^3 leaves) at a time.
constexpr int kBrickLog2 = 5;
constexpr int kBrick = 1 << kBrickLog2;
/// Cloud-in-cell weights are integers: each axis's weight in units of 2^-10 (the position
/// within its voxel rounded to 1/1024 voxel), their product in units of 2^-30, so a
/// particle's 8 weights sum to exactly 2^30 and the deposit conserves mass exactly. A
/// voxel's sum is at most the particle count (< 2^32) times 2^30, inside an int64.
constexpr std::int32_t kAxisUnit = 1024;
constexpr double kWeightUnit = double(kAxisUnit) * kAxisUnit * kAxisUnit;
/// Index coordinates are limited to +-2^20 voxels, as in voxelizeParticles.
constexpr float kMaxIndex = 1048576.0f;
/// Block and brick coordinates (|b| < 2^17, positions being checked to 2^20 voxels) as keys
/// ordered x-major, z fastest.
std::uint64_t blockKey(int bx, int by, int bz) { return packCoordKey(bx, by, bz); }
openvdb::Coord blockCoord(std::uint64_t key)
{
    const auto c = unpackCoordKey(key);
    return {c[0], c[1], c[2]};
}
inline int blockIndex(int x, int y, int z)  // x, y, z in [0, kBlock], the halo at kBlock
{
    return (x * kStored + y) * kStored + z;
}

/// floor for |x| < 2^31, exact (truncate, then step down when that moved x up).
inline int floorInt(float x)
{
    const int i = static_cast<int>(x);
    return i - (x < static_cast<float>(i) ? 1 : 0);
}

using Block = std::unique_ptr<std::int64_t[]>;

/// One thread's blocks; the blocks used lately are remembered, since consecutive particles
/// of a source lie in a few blocks.
struct LocalDeposit {
    std::unordered_map<std::uint64_t, Block> blocks;
    RecentLookup<std::int64_t> recent;
};

/// 1D blur taps, normalised to sum 1: w[t] for offsets t - taps, t in [0, 2 taps].
std::vector<float> blurTaps(double sigmaVoxels)
{
    const double variance = sigmaVoxels * sigmaVoxels - 1.0 / 6.0;  // less the deposit's tent
    if (variance <= 1e-4) return {1.0f};
    const double sigmaB = std::sqrt(variance);
    const int taps = static_cast<int>(std::ceil(3.0 * sigmaB));
    std::vector<double> w(2 * taps + 1);
    double sum = 0.0;
    for (int t = -taps; t <= taps; ++t) {
        w[t + taps] = std::exp(-0.5 * t * t / variance);
        sum += w[t + taps];
    }
    std::vector<float> out(w.size());
    for (std::size_t i = 0; i < w.size(); ++i) out[i] = static_cast<float>(w[i] / sum);
    return out;
}

}  // namespace

struct GaussianSplatter::Deposit {
    float invVoxel = 0.0f;
    std::uint64_t maxBytes = 0;
    std::atomic<std::uint64_t> bytes{0};
    tbb::enumerable_thread_specific<LocalDeposit> locals;

    std::int64_t* block(LocalDeposit& local, std::uint64_t key)
    {
        return local.recent.get(key, [&] { return newOrOldBlock(local, key); });
    }

    /// A zeroed block, counted against maxBytes.
    Block newBlock()
    {
        constexpr std::uint64_t kBytes = kBlockVoxels * sizeof(std::int64_t);
        const std::uint64_t total = bytes.fetch_add(kBytes) + kBytes;
        if (maxBytes != 0 && total > maxBytes)
            throw VoxelizeTooLarge("voxelize: the particles' deposit passes the limit of " +
                                   std::to_string(maxBytes >> 20) +
                                   " MiB; use larger voxels (voxelSize)");
        return Block(new std::int64_t[kBlockVoxels]());
    }

    /// Adds each block's halo layer into the blocks it belongs to (across the +x, +y and +z
    /// faces, edges and corner: 7 directions), making those that no particle's first corner
    /// reached, which join `summed` and are owned by `added`. One direction at a time, so that
    /// no block is written by two threads. Returns the blocks by key.
    std::unordered_map<std::uint64_t, const std::int64_t*> foldHalos(
        std::vector<std::pair<std::uint64_t, std::int64_t*>>& summed, std::vector<Block>& added)
    {
        // Direction o (1..7): bit 2 across x, bit 1 across y, bit 0 across z. Its part of the
        // halo: kBlock on the axes it crosses, [0, kBlock) on the others; it lands at 0 there.
        const auto forHaloOf = [](int o, auto&& visit) {
            int lo[3], hi[3];
            for (int a = 0; a < 3; ++a) {
                const bool across = (o >> (2 - a)) & 1;
                lo[a] = across ? kBlock : 0;
                hi[a] = across ? kBlock + 1 : kBlock;
            }
            for (int x = lo[0]; x < hi[0]; ++x)
                for (int y = lo[1]; y < hi[1]; ++y)
                    for (int z = lo[2]; z < hi[2]; ++z)
                        visit(blockIndex(x, y, z), blockIndex(x % kBlock, y % kBlock, z % kBlock));
        };
        const auto neighbour = [](std::uint64_t key, int o) {
            const openvdb::Coord c = blockCoord(key);
            return blockKey(c.x() + ((o >> 2) & 1), c.y() + ((o >> 1) & 1), c.z() + (o & 1));
        };
        const std::size_t reached = summed.size();
        std::vector<std::uint8_t> holds(reached, 0);  // bit o: the halo toward o is nonzero
        tbb::parallel_for(std::size_t(0), reached, [&](std::size_t u) {
            const std::int64_t* b = summed[u].second;
            for (int o = 1; o < 8; ++o)
                forHaloOf(o, [&](int from, int) {
                    if (b[from] != 0) holds[u] |= std::uint8_t(1u << o);
                });
        });
        std::unordered_map<std::uint64_t, std::int64_t*> byKey(2 * reached);
        for (const auto& [key, b] : summed) byKey.emplace(key, b);
        for (std::size_t u = 0; u < reached; ++u)
            for (int o = 1; o < 8; ++o) {
                if (!((holds[u] >> o) & 1)) continue;
                std::int64_t*& target = byKey[neighbour(summed[u].first, o)];
                if (target) continue;
                added.push_back(newBlock());
                target = added.back().get();
                summed.emplace_back(neighbour(summed[u].first, o), target);
            }
        for (int o = 1; o < 8; ++o)
            tbb::parallel_for(std::size_t(0), reached, [&](std::size_t u) {
                if (!((holds[u] >> o) & 1)) return;
                const std::int64_t* b = summed[u].second;
                std::int64_t* target = byKey.find(neighbour(summed[u].first, o))->second;
                forHaloOf(o, [&](int from, int to) { target[to] += b[from]; });
            });
        return {byKey.begin(), byKey.end()};
    }

    /// Frees every thread's blocks once the blur has read them.
    void releaseBlocks()
    {
        for (LocalDeposit& local : locals) {
            local.blocks.clear();
            local.recent.clear();
        }
    }

    std::int64_t* newOrOldBlock(LocalDeposit& local, std::uint64_t key)
    {
        Block& b = local.blocks[key];
        if (!b) {
            try {
                b = newBlock();
            } catch (...) {
                local.blocks.erase(key);
                throw;
            }
        }
        return b.get();
    }
};

double gaussianKernelSigma(double radius)
{
    const double pi = 3.14159265358979323846;
    // (2 pi)^(3/2) sigma^3 = the smooth kernel's integral: the same peak for the same mass.
    return std::cbrt(kernelIntegral(VoxelKernel::Smooth, radius)) / std::sqrt(2.0 * pi);
}

GaussianSplatter::GaussianSplatter(const VoxelizeSettings& settings)
    : mSettings(settings), mDeposit(std::make_unique<Deposit>())
{
    checkVoxelizeSettings(settings);
    mDeposit->invVoxel = static_cast<float>(1.0 / settings.voxelSize);
    mDeposit->maxBytes = settings.maxBytes;
}

GaussianSplatter::~GaussianSplatter() = default;

void GaussianSplatter::add(const float* xyz, std::size_t count)
{
    Deposit& d = *mDeposit;
    LocalDeposit& local = d.locals.local();
    for (std::size_t i = 0; i < count; ++i) {
        int c[3];
        std::int32_t w[3][2];
        for (int a = 0; a < 3; ++a) {
            const float q = xyz[3 * i + a] * d.invVoxel;
            if (!(std::fabs(q) < kMaxIndex))  // also catches NaN
                throw std::invalid_argument(
                    "voxelize: a particle position is not finite or lies "
                    "beyond 2^20 voxels from the origin");
            c[a] = floorInt(q);
            const std::int32_t f =
                static_cast<std::int32_t>((q - static_cast<float>(c[a])) * kAxisUnit + 0.5f);
            w[a][0] = kAxisUnit - f;
            w[a][1] = f;
        }
        constexpr int kLast = kBlock - 1;
        std::int64_t* b =
            d.block(local, blockKey(c[0] >> kBlockLog2, c[1] >> kBlockLog2, c[2] >> kBlockLog2)) +
            blockIndex(c[0] & kLast, c[1] & kLast, c[2] & kLast);
        for (int dx = 0; dx < 2; ++dx)
            for (int dy = 0; dy < 2; ++dy) {
                const std::int32_t wxy = w[0][dx] * w[1][dy];
                std::int64_t* row = b + blockIndex(dx, dy, 0);
                row[0] += wxy * w[2][0];
                row[1] += wxy * w[2][1];
            }
    }
    mCount.fetch_add(count);
}

namespace {

/// Blocks by key, as foldHalos returns them.
using BlockMap = std::unordered_map<std::uint64_t, const std::int64_t*>;
/// Blocks with their keys: the summed blocks in key order, then those foldHalos adds.
using KeyedBlocks = std::vector<std::pair<std::uint64_t, std::int64_t*>>;

/// One block per key: each key's blocks from every thread summed into the first of them, the
/// others freed. The weights are integers, so any order of summing gives the same deposit.
KeyedBlocks sumThreadBlocks(tbb::enumerable_thread_specific<LocalDeposit>& locals)
{
    std::vector<std::pair<std::uint64_t, Block*>> parts;
    for (LocalDeposit& local : locals)
        for (auto& [key, block] : local.blocks) parts.emplace_back(key, &block);
    std::sort(parts.begin(), parts.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<std::size_t> firsts;
    for (std::size_t i = 0; i < parts.size(); ++i)
        if (i == 0 || parts[i].first != parts[i - 1].first) firsts.push_back(i);
    firsts.push_back(parts.size());
    KeyedBlocks summed(firsts.size() - 1);
    tbb::parallel_for(std::size_t(0), summed.size(), [&](std::size_t u) {
        std::int64_t* sum = parts[firsts[u]].second->get();
        for (std::size_t j = firsts[u] + 1; j < firsts[u + 1]; ++j) {
            const std::int64_t* other = parts[j].second->get();
            for (int v = 0; v < kBlockVoxels; ++v) sum[v] += other[v];
            parts[j].second->reset();
        }
        summed[u] = {parts[firsts[u]].first, sum};
    });
    return summed;
}

/// The keys of the bricks the blur can reach, sorted: each block's voxels widened by `reach`
/// voxels on every side.
std::vector<std::uint64_t> bricksInReach(const KeyedBlocks& blocks, int reach)
{
    std::vector<std::uint64_t> bricks;
    for (const auto& block : blocks) {
        const openvdb::Coord b = blockCoord(block.first);
        int lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
            lo[a] = (b[a] * kBlock - reach) >> kBrickLog2;
            hi[a] = (b[a] * kBlock + kBlock - 1 + reach) >> kBrickLog2;
        }
        for (int x = lo[0]; x <= hi[0]; ++x)
            for (int y = lo[1]; y <= hi[1]; ++y)
                for (int z = lo[2]; z <= hi[2]; ++z) bricks.push_back(blockKey(x, y, z));
    }
    std::sort(bricks.begin(), bricks.end());
    bricks.erase(std::unique(bricks.begin(), bricks.end()), bricks.end());
    return bricks;
}

/// Throws VoxelizeTooLarge when `brickCount` blurred bricks beside the deposit's
/// `depositBytes` would pass maxBytes (0: no limit): checked before any brick is blurred, so
/// that a too large grid fails early.
void checkBricksFitLimit(std::uint64_t depositBytes, std::size_t brickCount, std::uint64_t maxBytes)
{
    constexpr std::uint64_t kBrickBytes = std::uint64_t(kBrick) * kBrick * kBrick * sizeof(float);
    if (maxBytes != 0 && depositBytes + brickCount * kBrickBytes > maxBytes)
        throw VoxelizeTooLarge("voxelize: the blurred grid would pass the limit of " +
                               std::to_string(maxBytes >> 20) +
                               " MiB; use larger voxels (voxelSize)");
}

/// Leaves (8^3 voxels) a brick holds.
constexpr int kLeaves = (kBrick / 8) * (kBrick / 8) * (kBrick / 8);

/// A box of voxels, [lo, hi] on each axis.
struct VoxelBox {
    int lo[3];
    int hi[3];
};

/// One thread's arrays for blurring a brick: the deposit with its margin (span^3), the passes
/// along z (span^2 kBrick) and y (span kBrick^2), and the brick's output (kBrick^3).
struct BlurScratch {
    std::vector<float> in, alongZ, alongY, out;
};

/// What blurs every brick alike: the deposit's blocks, the 1D taps and the density a unit of
/// deposited weight makes.
struct BrickBlur {
    BrickBlur(const BlockMap& depositBlocks, const std::vector<float>& kernelTaps,
              double densityPerWeight, bool clampToOne)
        : blocks(depositBlocks),
          taps(kernelTaps),
          scale(densityPerWeight),
          clamp(clampToOne),
          reach(static_cast<int>(kernelTaps.size() / 2)),
          span(kBrick + 2 * reach),
          width(static_cast<int>(kernelTaps.size()))
    {
    }

    const BlockMap& blocks;
    const std::vector<float>& taps;
    double scale;  ///< density per unit of deposited weight
    bool clamp;    ///< clamp the output to 1
    int reach;     ///< taps a side
    int span;      ///< voxels a side of the deposit gathered for a brick: kBrick + 2 reach
    int width;     ///< taps in all: 2 reach + 1
};

/// Fills in[x][y][z] with the deposit over [lo, lo + span)^3 converted to density, gathered
/// block by block; false when no block lies there.
bool gatherDeposit(const BrickBlur& blur, const openvdb::Coord& lo, std::vector<float>& in)
{
    const int span = blur.span;
    std::fill(in.begin(), in.end(), 0.0f);
    const openvdb::Coord firstBlock(lo.x() >> kBlockLog2, lo.y() >> kBlockLog2,
                                    lo.z() >> kBlockLog2);
    const openvdb::Coord lastBlock((lo.x() + span - 1) >> kBlockLog2,
                                   (lo.y() + span - 1) >> kBlockLog2,
                                   (lo.z() + span - 1) >> kBlockLog2);
    bool any = false;
    for (int bx = firstBlock.x(); bx <= lastBlock.x(); ++bx)
        for (int by = firstBlock.y(); by <= lastBlock.y(); ++by)
            for (int bz = firstBlock.z(); bz <= lastBlock.z(); ++bz) {
                const auto found = blur.blocks.find(blockKey(bx, by, bz));
                if (found == blur.blocks.end()) continue;
                any = true;
                const std::int64_t* b = found->second;
                const openvdb::Coord b0(bx * kBlock, by * kBlock, bz * kBlock);
                int from[3], to[3];
                for (int a = 0; a < 3; ++a) {
                    from[a] = std::max(b0[a], lo[a]);
                    to[a] = std::min(b0[a] + kBlock, lo[a] + span);
                }
                for (int x = from[0]; x < to[0]; ++x)
                    for (int y = from[1]; y < to[1]; ++y) {
                        const std::int64_t* src = b + blockIndex(x - b0.x(), y - b0.y(), 0);
                        float* dst = &in[(std::size_t(x - lo.x()) * span + (y - lo.y())) * span];
                        for (int z = from[2]; z < to[2]; ++z)
                            dst[z - lo.z()] = static_cast<float>(
                                static_cast<double>(src[z - b0.z()]) * blur.scale);
                    }
            }
    return any;
}

/// The box of `in` that holds the nonzero deposit (hi[0] < 0 when there is none): outside it
/// every term of the blur is w times +0, which leaves a sum unchanged, so the passes only run
/// over the box and what it reaches. Around sparse particles (vapour) that is a small part.
VoxelBox nonzeroBox(const std::vector<float>& in, int span)
{
    VoxelBox box{{span, span, span}, {-1, -1, -1}};
    for (int x = 0; x < span; ++x)
        for (int y = 0; y < span; ++y) {
            const float* row = &in[(std::size_t(x) * span + y) * span];
            const auto nonzero = [](float v) { return v != 0.0f; };
            const float* first = std::find_if(row, row + span, nonzero);
            if (first == row + span) continue;
            const float* last = std::find_if(std::make_reverse_iterator(row + span),
                                             std::make_reverse_iterator(row), nonzero)
                                    .base() -
                                1;
            box.lo[0] = std::min(box.lo[0], x), box.hi[0] = std::max(box.hi[0], x);
            box.lo[1] = std::min(box.lo[1], y), box.hi[1] = std::max(box.hi[1], y);
            box.lo[2] = std::min(box.lo[2], static_cast<int>(first - row));
            box.hi[2] = std::max(box.hi[2], static_cast<int>(last - row));
        }
    return box;
}

/// The brick's voxels the blur of `in` reaches: output voxel o sums in[o .. o + width - 1],
/// so it is nonzero only for o in [lo - width + 1, hi].
VoxelBox reachedBox(const VoxelBox& in, int width)
{
    VoxelBox out{};
    for (int a = 0; a < 3; ++a) {
        out.lo[a] = std::max(0, in.lo[a] - (width - 1));
        out.hi[a] = std::min(kBrick - 1, in.hi[a]);
    }
    return out;
}

/// The whole leaves that hold `box`: the output is kept leaf by leaf.
VoxelBox leafBox(const VoxelBox& box)
{
    VoxelBox leaves{};
    for (int a = 0; a < 3; ++a) {
        leaves.lo[a] = box.lo[a] & ~7;
        leaves.hi[a] = box.hi[a] | 7;
    }
    return leaves;
}

/// The first pass, along z: alongZ[x][y][z] for the rows of the nonzero box.
void blurAlongZ(const BrickBlur& blur, const VoxelBox& in, const VoxelBox& out, BlurScratch& s)
{
    const int span = blur.span;
    for (int x = in.lo[0]; x <= in.hi[0]; ++x)
        for (int y = in.lo[1]; y <= in.hi[1]; ++y) {
            const float* row = &s.in[(std::size_t(x) * span + y) * span];
            float* dst = &s.alongZ[(std::size_t(x) * span + y) * kBrick];
            std::fill(dst + out.lo[2], dst + out.hi[2] + 1, 0.0f);
            for (int t = 0; t < blur.width; ++t) {
                const float w = blur.taps[t];
                for (int z = out.lo[2]; z <= out.hi[2]; ++z) dst[z] += w * row[z + t];
            }
        }
}

/// The second pass, along y: alongY[x][y][z], the rows outside the nonzero box being zeros.
void blurAlongY(const BrickBlur& blur, const VoxelBox& in, const VoxelBox& out, BlurScratch& s)
{
    const int span = blur.span;
    for (int x = in.lo[0]; x <= in.hi[0]; ++x)
        for (int y = out.lo[1]; y <= out.hi[1]; ++y) {
            float* dst = &s.alongY[(std::size_t(x) * kBrick + y) * kBrick];
            std::fill(dst + out.lo[2], dst + out.hi[2] + 1, 0.0f);
            for (int t = std::max(0, in.lo[1] - y); t < blur.width && y + t <= in.hi[1]; ++t) {
                const float w = blur.taps[t];
                const float* row = &s.alongZ[(std::size_t(x) * span + y + t) * kBrick];
                for (int z = out.lo[2]; z <= out.hi[2]; ++z) dst[z] += w * row[z];
            }
        }
}

/// The last pass, along x: out[x][y][z], zeroed first over `leaves` so that the leaves the
/// box touches are whole.
void blurAlongX(const BrickBlur& blur, const VoxelBox& in, const VoxelBox& out,
                const VoxelBox& leaves, BlurScratch& s)
{
    for (int x = leaves.lo[0]; x <= leaves.hi[0]; ++x)
        for (int y = leaves.lo[1]; y <= leaves.hi[1]; ++y) {
            float* row = &s.out[(std::size_t(x) * kBrick + y) * kBrick];
            std::fill(row + leaves.lo[2], row + leaves.hi[2] + 1, 0.0f);
        }
    const int zCount = out.hi[2] - out.lo[2] + 1;
    for (int x = out.lo[0]; x <= out.hi[0]; ++x)
        for (int t = std::max(0, in.lo[0] - x); t < blur.width && x + t <= in.hi[0]; ++t) {
            const float w = blur.taps[t];
            for (int y = out.lo[1]; y <= out.hi[1]; ++y) {
                float* dst = &s.out[(std::size_t(x) * kBrick + y) * kBrick + out.lo[2]];
                const float* row =
                    &s.alongY[(std::size_t(x + t) * kBrick + y) * kBrick + out.lo[2]];
                for (int z = 0; z < zCount; ++z) dst[z] += w * row[z];
            }
        }
}

/// Cuts the output over `leaves` into OpenVDB leaves, each at its slot among the brick's
/// kLeaves (x-major); a leaf with nothing active stays null.
void keepLeaves(const std::vector<float>& out, const VoxelBox& leaves, const openvdb::Coord& origin,
                bool clamp, std::unique_ptr<LeafT>* brickLeaves)
{
    for (int x = leaves.lo[0]; x <= leaves.hi[0]; x += 8)
        for (int y = leaves.lo[1]; y <= leaves.hi[1]; y += 8)
            for (int z = leaves.lo[2]; z <= leaves.hi[2]; z += 8)
                brickLeaves[static_cast<std::size_t>(
                    ((x / 8) * (kBrick / 8) + y / 8) * (kBrick / 8) + z / 8)] =
                    leafFromDense(&out[(std::size_t(x) * kBrick + y) * kBrick + z], kBrick * kBrick,
                                  kBrick, origin + openvdb::Coord(x, y, z), clamp);
}

/// One brick: its deposit and a margin of `reach` voxels, converted to density, then blurred
/// along z, y and x; only the leaves holding something are kept in `brickLeaves`.
void blurBrick(const BrickBlur& blur, const openvdb::Coord& brick, BlurScratch& s,
               std::unique_ptr<LeafT>* brickLeaves)
{
    const openvdb::Coord origin(brick.x() * kBrick, brick.y() * kBrick, brick.z() * kBrick);
    const openvdb::Coord lo = origin - openvdb::Coord(blur.reach);  // first voxel of `in`
    if (!gatherDeposit(blur, lo, s.in)) return;
    const VoxelBox in = nonzeroBox(s.in, blur.span);
    if (in.hi[0] < 0) return;  // the deposit here rounded to zero
    const VoxelBox out = reachedBox(in, blur.width);
    blurAlongZ(blur, in, out, s);
    blurAlongY(blur, in, out, s);
    const VoxelBox leaves = leafBox(out);
    blurAlongX(blur, in, out, leaves, s);
    keepLeaves(s.out, leaves, origin, blur.clamp, brickLeaves);
}

/// Every brick blurred, in parallel: kLeaves slots a brick, in the bricks' order, null where
/// nothing is active. Each brick writes only its own slots, so the result does not depend on
/// the thread count.
std::vector<std::unique_ptr<LeafT>> blurBricks(const BrickBlur& blur,
                                               const std::vector<std::uint64_t>& bricks)
{
    std::vector<std::unique_ptr<LeafT>> leaves(bricks.size() * kLeaves);
    const int span = blur.span;
    tbb::enumerable_thread_specific<BlurScratch> scratch([&] {
        return BlurScratch{std::vector<float>(std::size_t(span) * span * span),
                           std::vector<float>(std::size_t(span) * span * kBrick),
                           std::vector<float>(std::size_t(span) * kBrick * kBrick),
                           std::vector<float>(std::size_t(kBrick) * kBrick * kBrick)};
    });
    tbb::parallel_for(std::size_t(0), bricks.size(), [&](std::size_t k) {
        blurBrick(blur, blockCoord(bricks[k]), scratch.local(), &leaves[k * kLeaves]);
    });
    return leaves;
}

/// The grid "density" (fog volume, background 0) that takes over the blurred leaves.
openvdb::FloatGrid::Ptr densityGrid(std::vector<std::unique_ptr<LeafT>>& leaves, double voxelSize)
{
    auto grid = openvdb::FloatGrid::create(0.0f);
    for (auto& leaf : leaves)
        if (leaf) grid->tree().addLeaf(leaf.release());
    grid->setName("density");
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(voxelSize));
    return grid;
}

}  // namespace

openvdb::FloatGrid::Ptr GaussianSplatter::finish(const std::function<void()>& checkCancelled)
{
    Deposit& d = *mDeposit;
    KeyedBlocks summed = sumThreadBlocks(d.locals);
    if (checkCancelled) checkCancelled();
    std::vector<Block> added;  // blocks that only halo layers reach
    const BlockMap blocks = d.foldHalos(summed, added);
    if (checkCancelled) checkCancelled();

    const double rv = mSettings.radius / mSettings.voxelSize;
    const std::vector<float> taps = blurTaps(gaussianKernelSigma(rv));
    const std::vector<std::uint64_t> bricks =
        bricksInReach(summed, static_cast<int>(taps.size() / 2));
    checkBricksFitLimit(d.bytes.load(), bricks.size(), d.maxBytes);

    // Each particle carries the kernel's integral (in voxels) times its peak density.
    const double mass = mSettings.density * kernelIntegral(VoxelKernel::Gaussian, rv);
    const BrickBlur blur(blocks, taps, mass / kWeightUnit, mSettings.clamp);
    std::vector<std::unique_ptr<LeafT>> leaves = blurBricks(blur, bricks);
    d.releaseBlocks();
    if (checkCancelled) checkCancelled();
    return densityGrid(leaves, mSettings.voxelSize);
}

}  // namespace cg::algo
