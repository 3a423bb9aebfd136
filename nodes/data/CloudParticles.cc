#include "nodes/data/CloudParticles.h"

#include <stdexcept>
#include <string>
#include <utility>

#include <tbb/parallel_for.h>

#include "core/Registry.h"
#include "nodes/data/ValueChecks.h"

namespace cg {

namespace {

template <class T>
void writeArray(ByteWriter& out, const algo::UninitArray<T>& a)
{
    out.u64(a.size());  // the layout of ByteWriter::podVector
    out.bytes(a.data(), a.size() * sizeof(T));
}

template <class T>
algo::UninitArray<T> readArray(ByteReader& in)
{
    if (in.remaining() < sizeof(std::uint64_t))
        checks::refuse("CloudParticles", "truncated payload");
    const std::uint64_t n = in.u64();
    if (n > in.remaining() / sizeof(T)) checks::refuse("CloudParticles", "truncated payload");
    algo::UninitArray<T> a(static_cast<std::size_t>(n));
    in.bytes(a.data(), a.size() * sizeof(T));
    return a;
}

DataPtr readCloudParticles(ByteReader& in)
{
    auto positions = readArray<float>(in);
    auto levels = readArray<std::uint8_t>(in);
    auto sources = readArray<std::uint32_t>(in);
    auto copyOrigins = readArray<float>(in);
    // Positions may honestly be non-finite (so may the condensation particles they grow
    // from): the voxelizer refuses those itself, and so copy origins.
    for (std::size_t i = 0; i < levels.size(); ++i)
        if (levels[i] > kMaxCloudLevel)
            checks::refuse("CloudParticles", "particle " + std::to_string(i) + " has level " +
                                                 std::to_string(levels[i]));
    // The constructor checks that the arrays agree in length and every source has an origin.
    return std::make_shared<CloudParticlesData>(std::move(positions), std::move(levels),
                                                std::move(sources), std::move(copyOrigins));
}

}  // namespace

namespace {

/// Throws std::invalid_argument unless the arrays agree in length and every particle's source
/// has a copy origin (when there are copy origins).
void checkArrays(const algo::CloudParticleArrays& a)
{
    if (a.positions.size() != 3 * a.levels.size() || a.sources.size() != a.levels.size())
        throw std::invalid_argument("CloudParticles: arrays differ in length");
    if (a.copyOrigins.size() % 3 != 0)
        throw std::invalid_argument("CloudParticles: copy origins are not xyz triples");
    if (!a.copyOrigins.empty()) {
        const std::size_t copies = a.copyOrigins.size() / 3;
        for (std::size_t i = 0; i < a.sources.size(); ++i)
            if (a.sources[i] >= copies)
                throw std::invalid_argument("CloudParticles: particle " + std::to_string(i) +
                                            " names source " + std::to_string(a.sources[i]) +
                                            ", which has no copy origin");
    }
}

/// Particles per chunk when the arrays are handed out in chunks.
constexpr std::size_t kArrayChunk = std::size_t(1) << 16;

}  // namespace

CloudParticlesData::CloudParticlesData(algo::UninitArray<float> positions,
                                       algo::UninitArray<std::uint8_t> levels,
                                       algo::UninitArray<std::uint32_t> sources,
                                       algo::UninitArray<float> copyOrigins)
    : mArrays{std::move(positions), std::move(levels), std::move(sources), std::move(copyOrigins)}
{
    checkArrays(mArrays);
    mHaveArrays = true;
}

CloudParticlesData::CloudParticlesData(const std::vector<float>& positions,
                                       const std::vector<std::uint8_t>& levels,
                                       const std::vector<std::uint32_t>& sources,
                                       const std::vector<float>& copyOrigins)
    : CloudParticlesData(
          algo::UninitArray<float>(positions), algo::UninitArray<std::uint8_t>(levels),
          algo::UninitArray<std::uint32_t>(sources), algo::UninitArray<float>(copyOrigins))
{
}

CloudParticlesData::CloudParticlesData(std::shared_ptr<const CloudParticleStream> stream)
    : mStream(std::move(stream))
{
    if (!mStream) throw std::invalid_argument("CloudParticles: no stream");
}

const algo::CloudParticleArrays& CloudParticlesData::arrays(
    const std::function<void()>& checkCancelled) const
{
    if (mHaveArrays) return mArrays;
    std::call_once(mMade, [&] {
        algo::CloudParticleArrays made = mStream->materialise(checkCancelled);
        checkArrays(made);
        mArrays = std::move(made);
        mHaveArrays = true;
    });
    return mArrays;
}

void CloudParticlesData::forEachChunk(const std::function<void(const algo::CloudChunk&)>& consume,
                                      CloudChunkFields fields,
                                      const std::function<void()>& checkCancelled) const
{
    const bool motion = fields.velocities || fields.ids;
    if (motion && !hasMotion())
        throw std::invalid_argument("these cloud particles carry no motion (velocities, ids)");
    // The arrays hold no motion: a stream gives it whether or not they were made.
    if (!mHaveArrays || motion) {
        mStream->forEachChunk(consume, fields, checkCancelled);
        return;
    }
    const std::size_t n = size();
    tbb::parallel_for(std::size_t(0), (n + kArrayChunk - 1) / kArrayChunk, [&](std::size_t c) {
        if (checkCancelled) checkCancelled();
        algo::CloudChunk chunk;
        chunk.first = c * kArrayChunk;
        chunk.count = std::min(kArrayChunk, n - c * kArrayChunk);
        chunk.positions = mArrays.positions.data() + 3 * chunk.first;
        chunk.levels = mArrays.levels.data() + chunk.first;
        if (fields.sources) {
            chunk.sources = mArrays.sources.data() + chunk.first;
            chunk.copyOrigins = mArrays.copyOrigins.data();
            chunk.copyCount = mArrays.copyOrigins.size() / 3;
        }
        consume(chunk);
    });
}

bool CloudParticlesData::hasMotion() const { return mStream && mStream->hasMotion(); }

std::size_t CloudParticlesData::byteSize() const
{
    // A stream not yet materialised holds only its inputs, which their own nodes account for.
    if (!mHaveArrays) return sizeof(*this);
    return sizeof(*this) + mArrays.positions.size() * sizeof(float) + mArrays.levels.size() +
           mArrays.sources.size() * 4 + mArrays.copyOrigins.size() * sizeof(float);
}

bool CloudParticlesData::serialize(ByteWriter& out) const
{
    const algo::CloudParticleArrays& a = arrays();
    writeArray(out, a.positions);
    writeArray(out, a.levels);
    writeArray(out, a.sources);
    writeArray(out, a.copyOrigins);
    return true;
}

void registerCloudParticlesType(Registry& registry)
{
    registry.addDataType(
        {"CloudParticles",
         "cloud particles of one frame: position, level, source id; the copy origin of each source",
         readCloudParticles});
}

}  // namespace cg
