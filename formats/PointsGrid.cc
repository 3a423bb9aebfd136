#include "formats/PointsGrid.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <openvdb/math/Math.h>
#include <openvdb/openvdb.h>
#include <openvdb/points/AttributeArray.h>
#include <openvdb/points/PointAttribute.h>

namespace cg::formats {

namespace {

namespace pts = openvdb::points;
using PointLeaf = pts::PointDataTree::LeafNodeType;
using CountTree = openvdb::tree::Tree4<std::uint32_t, 5, 4, 3>::Type;

/// OpenVDB's default voxel size for fewer than two particles or coincident ones, and the
/// decimal places computeVoxelSize keeps.
constexpr float kDefaultVoxelSize = 0.1f;
constexpr int kVoxelSizeDecimals = 5;

/// The voxel of a position (index space, the voxel centred on it) and the offset from the
/// voxel's centre, as createPointDataGrid computes them.
struct VoxelPlace {
    openvdb::Coord ijk;
    openvdb::Vec3f offset;
};
VoxelPlace placeOf(const openvdb::math::Transform& xform, const float* p)
{
    const openvdb::Vec3f world(p[0], p[1], p[2]);
    const openvdb::Coord ijk = xform.worldToIndexCellCentered(world);
    const openvdb::Vec3d index = xform.worldToIndex(world);
    return {ijk, openvdb::Vec3f(index - ijk.asVec3d())};
}

/// The cube root of volume / voxels, clamped to the volumes a ScaleMap allows; false when
/// it had to be clamped (computeVoxelSize's rule).
bool voxelSizeForVolume(double volume, std::size_t voxels, float& size)
{
    constexpr double kSmallest = 3e-15;
    constexpr double kLargest = std::numeric_limits<float>::max();
    double perVoxel = volume / static_cast<double>(voxels);
    const bool inRange = perVoxel >= kSmallest && perVoxel <= kLargest;
    perVoxel = std::clamp(perVoxel, kSmallest, kLargest);
    size = static_cast<float>(openvdb::math::Pow(perVoxel, 1.0 / 3.0));
    return inRange;
}

/// The size cut to `decimals` places, or to more where that would make it 0.
float truncated(float size, int decimals)
{
    float out = size;
    for (int d = decimals; d < 11; ++d) {
        out = static_cast<float>(openvdb::math::Truncate(double(size), d));
        if (out != 0.0f) break;
    }
    return out;
}

/// A leaf being filled: the leaf, and per voxel the next free point index.
struct FillSlot {
    PointLeaf* leaf = nullptr;
    std::unique_ptr<std::atomic<std::uint32_t>[]> next;
};

/// The values of an expanded, in-memory array as stored (encoded): moved without decoding,
/// since a fixed-point position decoded and encoded again need not come back the same.
template <class Array>
typename Array::StorageType* storedValues(pts::AttributeArray& array)
{
    return reinterpret_cast<typename Array::StorageType*>(
        const_cast<char*>(static_cast<Array&>(array).constDataAsByteArray()));
}

template <class Codec>
pts::PointDataGrid::Ptr buildWith(const ParticleChunks& chunks, double voxelSize)
{
    using PositionArray = pts::TypedAttributeArray<openvdb::Vec3f, Codec>;
    using LevelArray = pts::TypedAttributeArray<std::int32_t>;
    using SourceArray = pts::TypedAttributeArray<std::int64_t>;
    const auto xform = openvdb::math::Transform::createLinearTransform(voxelSize);

    // 1. Particles per voxel, summed over threads (integers: any order gives the same).
    tbb::enumerable_thread_specific<CountTree> perThread;
    chunks(
        [&](const ParticleChunk& c) {
            openvdb::tree::ValueAccessor<CountTree> acc(perThread.local());
            for (std::size_t i = 0; i < c.count; ++i) {
                const openvdb::Coord ijk = placeOf(*xform, c.xyz + 3 * i).ijk;
                acc.setValue(ijk, acc.getValue(ijk) + 1);
            }
        },
        false);
    CountTree counts;
    for (const CountTree& t : perThread) {
        openvdb::tree::ValueAccessor<CountTree> acc(counts);
        for (auto leaf = t.cbeginLeaf(); leaf; ++leaf)
            for (auto v = leaf->cbeginValueOn(); v; ++v) {
                const openvdb::Coord ijk = v.getCoord();
                acc.setValue(ijk, acc.getValue(ijk) + *v);
            }
    }
    perThread.clear();

    // 2. The point leaves with their offsets and attribute arrays, each voxel's next free
    // index at its first point.
    const auto descriptor = pts::AttributeSet::Descriptor::create(PositionArray::attributeType());
    auto grid = pts::PointDataGrid::create();
    grid->setTransform(xform);
    grid->setName("points");
    std::unordered_map<openvdb::Coord, FillSlot> slots;  // OpenVDB hashes a Coord
    std::vector<PointLeaf*> leaves;
    for (auto leaf = counts.cbeginLeaf(); leaf; ++leaf) {
        auto points = std::make_unique<PointLeaf>(leaf->origin());
        FillSlot slot;
        slot.next = std::make_unique<std::atomic<std::uint32_t>[]>(PointLeaf::SIZE);
        std::vector<PointLeaf::ValueType> offsets(PointLeaf::SIZE);
        std::uint32_t end = 0;
        for (openvdb::Index n = 0; n < PointLeaf::SIZE; ++n) {
            slot.next[n].store(end, std::memory_order_relaxed);
            end += leaf->isValueOn(n) ? leaf->getValue(n) : 0;
            offsets[n] = end;
        }
        points->setOffsets(offsets);
        points->initializeAttributes(descriptor, end);
        slot.leaf = points.get();
        leaves.push_back(points.get());
        slots.emplace(leaf->origin(), std::move(slot));
        grid->tree().addLeaf(points.release());
    }
    counts.clear();
    pts::appendAttribute<std::int32_t>(grid->tree(), "level");
    pts::appendAttribute<std::int64_t>(grid->tree(), "source");
    if (leaves.empty()) return grid;
    const auto& attributes = leaves.front()->attributeSet().descriptor();
    const std::size_t levelIndex = attributes.find("level"),
                      sourceIndex = attributes.find("source");
    tbb::parallel_for(std::size_t(0), leaves.size(), [&](std::size_t l) {
        for (std::size_t a = 0; a < leaves[l]->attributeSet().size(); ++a)
            leaves[l]->attributeArray(a).expand(/*fill=*/false);  // every value is set below
    });

    // 3. Every particle into the next free index of its voxel, its source tagged with its
    // index in the frame (high 32 bits), which puts each voxel back in particle order next.
    chunks(
        [&](const ParticleChunk& c) {
            for (std::size_t i = 0; i < c.count; ++i) {
                const VoxelPlace place = placeOf(*xform, c.xyz + 3 * i);
                FillSlot& slot =
                    slots.find(place.ijk & ~static_cast<openvdb::Int32>(PointLeaf::DIM - 1))
                        ->second;
                const openvdb::Index n = PointLeaf::coordToOffset(place.ijk);
                const std::uint32_t at = slot.next[n].fetch_add(1, std::memory_order_relaxed);
                PointLeaf& leaf = *slot.leaf;
                static_cast<PositionArray&>(leaf.attributeArray(0)).setUnsafe(at, place.offset);
                static_cast<LevelArray&>(leaf.attributeArray(levelIndex))
                    .setUnsafe(at, c.levels[i]);
                const std::uint64_t tagged = ((c.first + i) << 32) | c.sources[i];
                static_cast<SourceArray&>(leaf.attributeArray(sourceIndex))
                    .setUnsafe(at, static_cast<std::int64_t>(tagged));
            }
        },
        true);

    // 4. Each voxel in particle order, the tags removed.
    tbb::parallel_for(std::size_t(0), leaves.size(), [&](std::size_t l) {
        PointLeaf& leaf = *leaves[l];
        auto* position = storedValues<PositionArray>(leaf.attributeArray(0));
        auto* level = storedValues<LevelArray>(leaf.attributeArray(levelIndex));
        auto* source = storedValues<SourceArray>(leaf.attributeArray(sourceIndex));
        std::vector<std::uint32_t> order;
        std::vector<typename PositionArray::StorageType> positions;
        std::vector<std::int32_t> levels;
        std::vector<std::int64_t> sources;
        std::uint32_t begin = 0;
        for (openvdb::Index n = 0; n < PointLeaf::SIZE; ++n) {
            const std::uint32_t end = leaf.getValue(n);
            if (end - begin > 1) {
                order.resize(end - begin);
                std::iota(order.begin(), order.end(), begin);
                std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
                    return static_cast<std::uint64_t>(source[a]) <
                           static_cast<std::uint64_t>(source[b]);
                });
                positions.clear(), levels.clear(), sources.clear();
                for (const std::uint32_t i : order) {
                    positions.push_back(position[i]);
                    levels.push_back(level[i]);
                    sources.push_back(source[i]);
                }
                std::copy(positions.begin(), positions.end(), position + begin);
                std::copy(levels.begin(), levels.end(), level + begin);
                std::copy(sources.begin(), sources.end(), source + begin);
            }
            begin = end;
        }
        for (std::uint32_t i = 0; i < begin; ++i)
            source[i] =
                static_cast<std::int64_t>(static_cast<std::uint64_t>(source[i]) & 0xffffffffu);
        leaf.attributeArray(levelIndex).compact();
        leaf.attributeArray(sourceIndex).compact();
    });

    return grid;
}

}  // namespace

ParticlePointsGridBuilder::ParticlePointsGridBuilder(ParticleChunks chunks,
                                                     const PointsGridSettings& settings)
    : mChunks(std::move(chunks)), mSettings(settings)
{
    if (!(settings.voxelSize >= 0.0) || !std::isfinite(settings.voxelSize))
        throw std::invalid_argument("points grid: voxel size must be >= 0 (0 = automatic)");
    if (settings.pointsPerVoxel < 1)
        throw std::invalid_argument("points grid: points per voxel must be >= 1");
    struct Survey {
        std::uint64_t count = 0;
        openvdb::Vec3f min{std::numeric_limits<float>::max()},
            max{-std::numeric_limits<float>::max()};
        std::uint64_t firstBad = std::numeric_limits<std::uint64_t>::max();
    };
    tbb::enumerable_thread_specific<Survey> surveys;
    mChunks(
        [&](const ParticleChunk& c) {
            Survey& s = surveys.local();
            s.count += c.count;
            for (std::size_t i = 0; i < c.count; ++i) {
                const openvdb::Vec3f p(c.xyz[3 * i], c.xyz[3 * i + 1], c.xyz[3 * i + 2]);
                if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
                    s.firstBad = std::min<std::uint64_t>(s.firstBad, c.first + i);
                    continue;
                }
                s.min = openvdb::math::minComponent(s.min, p);
                s.max = openvdb::math::maxComponent(s.max, p);
            }
        },
        false);
    Survey all;
    for (const Survey& s : surveys) {
        all.count += s.count;
        all.min = openvdb::math::minComponent(all.min, s.min);
        all.max = openvdb::math::maxComponent(all.max, s.max);
        all.firstBad = std::min(all.firstBad, s.firstBad);
    }
    if (all.firstBad != std::numeric_limits<std::uint64_t>::max())
        throw std::invalid_argument("points grid: particle " + std::to_string(all.firstBad) +
                                    " has a non-finite position");
    // Particle indices tag the sources while a grid is filled (see buildWith).
    if (all.count >= (std::uint64_t(1) << 32))
        throw std::invalid_argument("points grid: 2^32 particles or more in one frame");
    mCount = all.count;
    mMin = all.min;
    mMax = all.max;
}

std::size_t ParticlePointsGridBuilder::occupiedVoxels(float voxelSize) const
{
    const auto xform = openvdb::math::Transform::createLinearTransform(voxelSize);
    tbb::enumerable_thread_specific<openvdb::MaskTree> masks;
    mChunks(
        [&](const ParticleChunk& c) {
            openvdb::tree::ValueAccessor<openvdb::MaskTree> acc(masks.local());
            for (std::size_t i = 0; i < c.count; ++i)
                acc.setValueOn(placeOf(*xform, c.xyz + 3 * i).ijk);
        },
        false);
    openvdb::MaskTree all;
    for (const openvdb::MaskTree& m : masks) all.topologyUnion(m);
    return static_cast<std::size_t>(all.activeVoxelCount());
}

// OpenVDB's computeVoxelSize, over chunks: from the bounding box's volume shared among the
// target number of voxels, shrink while the occupied voxels' volume keeps falling by more
// than a tenth in edge.
double ParticlePointsGridBuilder::voxelSize() const
{
    if (mSettings.voxelSize > 0.0) return mSettings.voxelSize;
    if (mCount == 0) return 1.0;  // nothing to measure; one voxel per metre is as good as any
    if (mCount <= 1) return kDefaultVoxelSize;
    const std::size_t target = std::max<std::size_t>(
        1, static_cast<std::size_t>(mCount) / static_cast<std::size_t>(mSettings.pointsPerVoxel));
    const openvdb::BBoxd box(mMin, mMax);
    if (box.min() == box.max()) return kDefaultVoxelSize;
    double volume = box.volume();
    if (openvdb::math::isApproxZero(volume)) {  // collinear or coplanar particles
        const openvdb::Vec3d e = box.extents().sorted().reversed();
        volume = openvdb::math::isApproxZero(e[1]) ? e[0] * e[0] * e[0] : e[0] * e[1] * e[1];
    }
    float size = kDefaultVoxelSize;
    if (!voxelSizeForVolume(volume, target, size)) return size;
    double previousVolume = volume;
    std::size_t previousVoxels = 0, voxels = 1;
    while (voxels > previousVoxels) {
        previousVoxels = voxels;
        voxels = occupiedVoxels(size);
        volume = openvdb::math::Pow3(size) * static_cast<float>(voxels);
        if (volume >= previousVolume) break;
        previousVolume = volume;
        const float previous = size;
        if (!voxelSizeForVolume(volume, target, size)) {
            size = previous;
            break;
        }
        if (size / previous > 0.9f) break;
    }
    return truncated(size, kVoxelSizeDecimals);
}

openvdb::points::PointDataGrid::Ptr ParticlePointsGridBuilder::build() const
{
    const double size = voxelSize();
    return mSettings.precision == PointPrecision::Fixed16
               ? buildWith<pts::FixedPointCodec</*OneByte=*/false>>(mChunks, size)
               : buildWith<pts::NullCodec>(mChunks, size);
}

openvdb::points::PointDataGrid::Ptr makeParticlePointsGrid(const float* xyz,
                                                           const std::uint8_t* levels,
                                                           const std::uint32_t* sources,
                                                           std::size_t count,
                                                           const PointsGridSettings& settings)
{
    constexpr std::size_t kChunk = std::size_t(1) << 16;
    const ParticleChunks chunks = [=](const std::function<void(const ParticleChunk&)>& consume,
                                      bool attributes) {
        tbb::parallel_for(std::size_t(0), (count + kChunk - 1) / kChunk, [&](std::size_t k) {
            const std::size_t first = k * kChunk;
            consume({first, std::min(kChunk, count - first), xyz + 3 * first,
                     attributes ? levels + first : nullptr,
                     attributes ? sources + first : nullptr});
        });
    };
    return ParticlePointsGridBuilder(chunks, settings).build();
}

}  // namespace cg::formats
